#pragma once
// report.html of `snapfit run`: one self-contained page (report/html_page.h) that plays
// the haptic loop's recorded poses in 3D with the force and torque sent to the device,
// colours the triangles that are inside the other part (report/part_contact.h), draws the
// loop's time series with a cursor that follows the playback, the tuning curve and the
// field figures, and puts the summary at the top. Long runs are thinned for display
// (report/loop_display.h); loop.csv keeps every frame.
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "snapfit/job.h"
#include "snapfit/mesh.h"
#include "snapfit/pose_json.h"

namespace snapfit {

struct RunPageLimits {
  std::size_t playback_frames = 1500;     // poses the 3D view plays, evenly spaced over the run
  std::size_t chart_points = 4000;        // points a time series (min/max envelopes beyond)
  std::size_t display_triangles = 40000;  // a part, after refinement for the contact colouring
  std::size_t contact_bits = 8000000;     // inside-flags over all frames that carry them
  std::size_t missed_points = 2000;       // missed frames marked on the frame-time chart
};

// A PNG figure shown in the page, with its caption.
struct PageFigure {
  std::string caption;
  std::vector<unsigned char> png;
};

// The part as the page draws it: `mesh` refined (mesh/triangle_refine.h) until no piece is
// wider than about the field grid's spacing, or coarser where that would pass
// max_triangles; a mesh already above max_triangles as it is.
Mesh display_mesh(const Mesh& mesh, double spacing, std::size_t max_triangles);

// A part for the pages' 3D view: a triangle soup, 9 float32 a triangle, in base64.
nlohmann::json part_json(const std::string& name, const Mesh& mesh);

// The page's data block (report/web/src/run_report.js reads it).
nlohmann::json run_page_data(const JobResult& run, const std::vector<PageFigure>& figures,
                             const RunPageLimits& limits = {});

// Writes report.html to `path`. Throws snapfit::Error when this build has no web report.
void write_run_page(const std::string& path, const JobResult& run, const std::vector<PageFigure>& figures,
                    const RunPageLimits& limits = {});

}  // namespace snapfit
