#pragma once
// The report folder `snapfit run` writes (results/<scene>/): summary.json, both parts as
// STL, a figure of each part's affinity through y = 0 of its frame (seed 000 Fig. 2
// style, report/slice_figure.h), the haptic loop's log (report/haptic_report.h), and
// report.html (report/run_page.h), which shows all of it in a browser.
#include <filesystem>
#include <string>
#include <vector>

#include "snapfit/job.h"

namespace snapfit {

// Writes every file into `out` (created); returns their names, summary.json first.
// report.html is left out, and summary.json says so, when this build has no web report
// (report/web_assets.h). Throws snapfit::Error naming the file that cannot be written.
std::vector<std::string> write_run_report(const std::filesystem::path& out, const JobResult& run);

struct RunReportFiles {
  std::vector<std::string> written;   // summary.json first
  std::vector<std::string> warnings;  // what the folder lacks and why (no report.html, unreadable labels)
};

// write_run_report for a job that has taken `seconds` so far, with what the folder lacks.
RunReportFiles write_job_report(const std::filesystem::path& out, JobResult& run, double seconds);

}  // namespace snapfit
