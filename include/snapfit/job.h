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
#include <array>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "snapfit/accuracy.h"
#include "snapfit/haptic_loop.h"
#include "snapfit/job_facts.h"
#include "snapfit/scene.h"
#include "snapfit/tuning.h"

namespace snapfit {

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

// What the job built and measured, as plain data: enough to draw its report folder
// (the tool's report/ stage reads nothing else).
struct JobResult {
  Scene scene;              // as the job ran it
  std::string device;       // where the fields and spectra were computed ("host" for the VPS peer)
  std::string driver;       // that device's driver version
  bool device_check_passed = false;
  std::string loop_device;  // where the loop ran
  JobPart part1, part2;
  const JobPart& part(int part) const { return part == 1 ? part1 : part2; }
  std::vector<std::string> plan;  // the compute plan, one sentence per decision with its reason
  double spacing = 0;             // the grid spacing both parts' fields share, scene units
  std::array<std::size_t, 3> fft_dims{};  // the spectra's FFT grid (zeros for the VPS peer)
  // The query strategy the loop renders and why: variant_name() of the loop's engine ("" for
  // the VPS peer), the same short (strategy_short_name), how it was chosen ("lowest error
  // that fits (measured)", "... (strategy file)", "JobRequest::strategy", "JobRequest::modes
  // (not measured)", "safe start ..."), the measured candidates when chosen by error, and
  // the strategy file that keeps them.
  std::string strategy;
  std::string strategy_label;
  std::string strategy_chosen_by;
  std::optional<AccuracyReport> strategies;
  std::string strategy_file;
  TuningResult tuning;      // m' for the loop (chosen_modes); empty for the VPS peer
  std::string tuning_key;   // the tuning file's key; "" when m' was fixed (JobRequest::modes)
  std::optional<LoopReport> loop;        // the scripted session, when the scene has a trajectory
  std::optional<SessionFacts> session;   // its set-up and its end, with the loop
  std::optional<VpsFacts> vps;           // set for a scene whose method is "vps" or "vps_hybrid"
  double seconds = 0;                    // the whole job so far
  double seconds_to_first_frame = 0;     // from the job's start to the loop's first frame (0: no loop)
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
};

// Runs the job. Throws snapfit::Error naming the part, file, device or step that failed
// (a device that fails its self-check is one).
JobResult run_job(const Scene& scene, const JobRequest& request = {});

}  // namespace snapfit
