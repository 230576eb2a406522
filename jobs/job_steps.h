#pragma once
// What the main job's steps share: the request's text callbacks with their defaults,
// and the scripted-session step both methods end with.
#include <functional>
#include <memory>
#include <string>

#include "engine/query/query_engine.h"
#include "jobs/job_record.h"
#include "scheduler/tuning/loop_devices.h"
#include "snapfit/job.h"

namespace snapfit {

struct JobOutput {
  std::function<void(const std::string&)> say;   // never empty
  std::function<void(const std::string&)> note;  // never empty
};

// The request's callbacks, silent `say` and stderr `note` where it has none.
JobOutput job_output(const JobRequest& request);

// The scene's trajectory played through the loop's "[7/7]" step: `play` runs the
// session; `what` names the method in the step's line.
void run_session_step(const Scene& scene, const JobRequest& request, const JobOutput& out, const std::string& what,
                      JobRecord& record, const std::function<SessionResult(const SessionOptions&)>& play);

// "[2/7]": both parts built and validated, the scene and plan said; checks the request
// first (margin, strategy).
std::shared_ptr<AssemblyPair> prepare_job_parts(const Scene& scene, const JobRequest& request, const JobOutput& out);

// The main job up to the loop ("[3/7]" to "[6/7]"), the snapfit method: the device and
// its self-check, the fields and spectra, the strategy and m'; the engine the loop
// renders, with what keeps it alive.
struct PreparedJob {
  std::shared_ptr<JobRecord> record;
  std::shared_ptr<AssemblyPair> pair;
  std::unique_ptr<ComputeContext> ctx;
  std::unique_ptr<QueryEngine> fixed_engine;  // with a fixed m'
  std::unique_ptr<LoopDevices> devices;       // tuned: the loop's device among them
  QueryEngine* loop_engine = nullptr;
};
PreparedJob prepare_job(const Scene& scene, const JobRequest& request, const JobOutput& out,
                        std::shared_ptr<AssemblyPair> pair);

// The public result, as plain data: the record's summary and everything its report shows.
// The parts' meshes and fields are shared with the record's pair, not copied; the
// session's log is moved out of the record.
JobResult job_result(JobRecord record);

// A scene whose method is "vps" or "vps_hybrid": the Voxmap PointShell peer on the host
// (scheduler/vps/), through the same loop; `pair` holds the prepared parts.
JobResult run_vps_job(std::shared_ptr<AssemblyPair> pair, const JobRequest& request, const JobOutput& out);

}  // namespace snapfit
