#include "jobs/job_steps.h"

#include <iostream>
#include <sstream>

#include "jobs/job_text.h"

namespace snapfit {

JobOutput job_output(const JobRequest& request) {
  JobOutput out;
  out.say = request.say ? request.say : [](const std::string&) {};
  out.note = request.note ? request.note : [](const std::string& m) { std::cerr << "snapfit: " << m << "\n"; };
  return out;
}

void run_session_step(const Scene& scene, const JobRequest& request, const JobOutput& out, const std::string& what,
                      JobRecord& record, const std::function<SessionResult(const SessionOptions&)>& play) {
  if (scene.trajectory.keyframes.empty()) {
    out.say("[7/7] the scene has no trajectory: no scripted assembly to run\n");
    return;
  }
  const Trajectory& t = scene.trajectory;
  const double seconds = t.keyframes.back().time_s - t.keyframes.front().time_s + scene.haptics.settle_s;
  std::ostringstream line;
  line << "[7/7] haptic loop at " << scene.loop_rate_hz << " Hz playing the scripted trajectory (" << seconds
       << " s of " << (request.simulated_time ? "simulated" : "real") << " time, " << what << ")\n";
  out.say(line.str());
  SessionOptions session;
  session.simulated_time = request.simulated_time;
  session.wait = request.loop_wait;
  record.session = play(session);
  const SessionResult& s = *record.session;
  if (s.priority.failed)
    out.note("could not raise the priority of " + std::to_string(s.priority.failed) + " threads for the loop (" +
             s.priority.reason + "); frames may be late on a busy machine");
  if (!s.contact_off.empty()) out.note(s.contact_off);
  out.say(session_text(scene, s));
}

JobResult job_result(JobRecord record) {
  JobResult r;
  const AssemblyPair& pair = *record.pair;
  r.scene = pair.scene;
  r.device = record.device.name;
  r.driver = record.device.driver_version;
  r.device_check_passed = record.check.passed;
  r.loop_device = record.loop_device.name;
  for (int i = 1; i <= 2; ++i) {
    JobPart& part = i == 1 ? r.part1 : r.part2;
    part.mesh = std::shared_ptr<const Mesh>(record.pair, &pair.part(i).mesh);
    part.report = pair.part(i).report;
    part.cad = pair.part(i).cad;
    if (!record.vps) part.fields = std::shared_ptr<const PartFieldsResult>(record.pair, &pair.fields(i));
  }
  r.plan = pair.plan.lines;
  r.spacing = pair.grids.spacing;
  if (!record.vps) r.fft_dims = pair.spectra.dims;
  r.strategy = record.strategy;
  r.strategy_label = record.strategy_label;
  r.strategy_chosen_by = record.strategy_chosen_by;
  r.strategies = std::move(record.strategies);
  r.strategy_file = record.strategy_file;
  r.tuning = record.tuning;
  r.tuning_key = record.tuning_key;
  if (record.session) {
    SessionResult& s = *record.session;
    SessionFacts& facts = r.session.emplace(s);
    if (s.contact) facts.rigid_contact = rigid_contact_facts(*s.contact);
    r.loop = std::move(s.loop);
    r.evaluated = s.evaluated;
    r.assembled = s.assembled;
    r.final_position_error = s.final_error.position;
    r.final_angle_deg = s.final_error.angle_deg;
    r.final_surface_deviation = s.surface_deviation;
  }
  r.vps = std::move(record.vps);
  r.seconds = record.seconds;
  r.seconds_to_first_frame = record.seconds_to_first_frame;
  return r;
}

}  // namespace snapfit
