#pragma once
// The main job, as `snapfit run` does it, in one call: both parts built and validated,
// the OpenCL device opened and self-checked, both parts' descriptor fields and their
// spectra computed (or read from the caches), the query strategy and m' chosen for the
// scene's frame budget on this device (tuning.h), and the scene's scripted trajectory
// played through the haptic loop (haptic_loop.h). A scene whose method is "vps" or
// "vps_hybrid" runs the Voxmap PointShell peer (Faas 2010) in the same loop instead, on
// the host.
//
//   snapfit::JobRequest request;
//   request.say = [](const std::string& text) { std::cout << text; };
//   snapfit::JobResult r = snapfit::run_job(snapfit::load_scene("scenes/default.json"), request);
//   // r.assembled, r.loop->measured_rate_hz, r.tuning.chosen_modes, ...
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "snapfit/haptic_loop.h"
#include "snapfit/scene.h"
#include "snapfit/tuning.h"

namespace snapfit {

// Everything the job built and measured (parts, fields, spectra, the strategies'
// errors, the session's log), for the tool's report; its type is not part of the
// public API.
struct JobRecord;

struct JobRequest {
  // The OpenCL device (as AssemblyOptions::device). With "" the other devices are tuned
  // too and the loop goes to the one that fits the most modes.
  std::string device;
  std::size_t modes = 0;  // a fixed m' instead of the tuned one; 0: tuned
  double margin = 0.25;   // tuning: p99 at most (1 - margin) of the frame budget
  bool retune = false;    // measure m' and the strategies' errors even when their files match
  // The query strategy: "auto" (the lowest error of the rendered wrench that fits the
  // frame, most_accurate_strategy in tuning.h; tricubic with a fixed m'), "tricubic",
  // "trilinear", "exact-product" or "near-far" (the exact product's sum split into near and
  // far parts, QueryVariant::near_far).
  std::string strategy = "auto";
  bool simulated_time = false;  // the loop on simulated time: deterministic, no timing meaning
  LoopWait loop_wait = LoopWait::spin;
  bool progress = false;  // progress bars on stderr
  // The job's steps and measurements as text for people, a line or a table at a time,
  // each ending in a newline (`snapfit run` prints them on stdout); default: silent.
  std::function<void(const std::string&)> say;
  // Warnings and cache messages, one line each, no newline; default: stderr.
  std::function<void(const std::string&)> note;
};

struct JobResult {
  std::string device;       // where the fields and spectra were computed ("host" for the VPS peer)
  std::string loop_device;  // where the loop ran
  std::string strategy;     // variant_name() of the loop's engine ("" for the VPS peer)
  std::string strategy_chosen_by;
  TuningResult tuning;              // m' for the loop (chosen_modes); empty for the VPS peer
  std::optional<LoopReport> loop;   // the scripted session, when the scene has a trajectory
  bool evaluated = false;           // the scene has an assembled pose to judge the end against
  // evaluated, and the final pose within the scene's position and angle tolerances, or
  // part 2's surface within the position tolerance of where the assembled pose puts it
  // (a round peg turned about its own axis is assembled)
  bool assembled = false;
  double final_position_error = 0;  // scene units
  double final_angle_deg = 0;
  // The two-sided Hausdorff distance between part 2's surface at the final pose and at
  // the assembled pose, scene units
  double final_surface_deviation = 0;
  std::shared_ptr<JobRecord> record;
};

// Runs the job. Throws snapfit::Error naming the part, file, device or step that failed
// (a device that fails its self-check is one).
JobResult run_job(const Scene& scene, const JobRequest& request = {});

}  // namespace snapfit
