#include "report/haptic_report.h"

#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>

#include "report/chart_spec.h"
#include "report/loop_json.h"
#include "snapfit/export.h"
#include "snapfit/pose_json.h"
#include "snapfit/quantile.h"

namespace snapfit {
namespace {

std::string loop_csv(const LoopReport& loop) {
  std::ostringstream csv;
  csv.precision(9);
  csv << "time_s,frame_ms,missed,modes,flags,device_x,device_y,device_z,part_x,part_y,part_z,part_qw,part_qx,"
         "part_qy,part_qz,energy,geo_fx,geo_fy,geo_fz,geo_tx,geo_ty,geo_tz,sent_fx,sent_fy,sent_fz,sent_tx,"
         "sent_ty,sent_tz,energy_error_est,geo_force_error_est,geo_torque_error_est,contact_fx,contact_fy,contact_fz,"
         "contact_tx,contact_ty,contact_tz,contact_depth,constraint,constraint_x,trust\n";
  for (const FrameRecord& f : loop.log) {
    const Eigen::Vector3d& d = f.device.translation;
    const Eigen::Vector3d& p = f.part.translation;
    const Eigen::Quaterniond& q = f.part.rotation;
    csv << f.time_s << ',' << f.frame_ms << ',' << f.missed << ',' << f.modes << ',' << f.flags << ',' << d.x() << ','
        << d.y() << ',' << d.z() << ',' << p.x() << ',' << p.y() << ',' << p.z() << ',' << q.w() << ',' << q.x() << ','
        << q.y() << ',' << q.z() << ',' << f.energy;
    for (const Eigen::Vector3d* v : {&f.geometric.force, &f.geometric.torque, &f.sent.force, &f.sent.torque})
      csv << ',' << v->x() << ',' << v->y() << ',' << v->z();
    csv << ',' << f.geometric_error.energy << ',' << f.geometric_error.force << ',' << f.geometric_error.torque;
    for (const Eigen::Vector3d* v : {&f.contact.force, &f.contact.torque})
      csv << ',' << v->x() << ',' << v->y() << ',' << v->z();
    csv << ',' << f.contact_depth << ',' << static_cast<int>(f.constraint) << ',' << f.constraint_weight << ','
        << f.trust << '\n';
  }
  return csv.str();
}

}  // namespace

Chart tuning_chart(const TuningResult& t, const std::string& device_name) {
  Series p50{"p50", {}, {}, Series::Style::line_points, ""}, p99{"p99", {}, {}, Series::Style::line_points, ""},
      model{"cost model (p99 fit)", {}, {}, Series::Style::line, ""};
  for (const TimingPoint& p : t.points) {
    p50.x.push_back(p.modes), p50.y.push_back(p.p50_ms);
    p99.x.push_back(p.modes), p99.y.push_back(p.p99_ms);
    model.x.push_back(p.modes), model.y.push_back(std::max(1e-3, t.model.predict_ms(p.modes)));
  }
  Chart c;
  c.title = "Per-query time against m' on " + device_name;
  c.x_label = "m' (modes)";
  c.y_label = "ms per query";
  c.log_x = c.log_y = true;
  c.series = {p50, p99, model};
  c.hlines.push_back(HLine{t.budget_ms, "budget"});
  c.hlines.push_back(HLine{t.target_ms(), "target (margin)"});
  for (const TimingPoint& p : t.points)
    if (p.modes == t.chosen_modes) c.markers.push_back(Marker{double(p.modes), p.p99_ms, "chosen m'"});
  c.markers.push_back(Marker{4096, t.model.predict_ms(4096) > 0 ? t.model.predict_ms(4096) : t.points.front().p99_ms,
                             "seed 000: 4096 (K20c)"});
  return c;
}

nlohmann::json stiffness_json(const RenderedStiffness& k) {
  const auto six = [](const std::array<double, 6>& v) {
    return nlohmann::json{{"+x", v[0]}, {"-x", v[1]}, {"+y", v[2]}, {"-y", v[3]}, {"+z", v[4]}, {"-z", v[5]}};
  };
  return {{"step_mm", k.step_mm},
          {"tilt_deg", k.tilt_deg},
          {"force_n_per_mm", six(k.force_n_per_mm)},
          {"torque_nm_per_deg", six(k.torque_nm_per_deg)},
          {"coupling_n_per_mm", k.coupling_n_per_mm},
          {"coupling_nm_per_deg", k.coupling_nm_per_deg}};
}

nlohmann::json write_haptic_report(const std::filesystem::path& out, const SessionFacts& run, const LoopReport& loop,
                                   const TuningResult& tuning) {
  write_text_file((out / "loop.csv").string(), loop_csv(loop));

  // The engine's per-frame error estimate of the geometric wrench (include/snapfit/query.h).
  std::vector<double> force_error, torque_error;
  for (const FrameRecord& f : loop.log)
    if (f.flags == 0) force_error.push_back(f.geometric_error.force), torque_error.push_back(f.geometric_error.torque);
  const auto spread = [](const std::vector<double>& v) -> nlohmann::json {
    if (v.empty()) return nullptr;
    return {{"p50", quantile(v, 0.5)}, {"p95", quantile(v, 0.95)}, {"max", quantile(v, 1.0)}};
  };
  const auto& fp = loop.final_part.pose;
  // The rigid contact and the stiffness the user feels at the fit.
  nlohmann::json contact = nullptr;
  if (!run.contact_off.empty()) contact = {{"off", run.contact_off}};
  if (run.rigid_contact) {
    const RigidContactFacts& m = *run.rigid_contact;
    std::size_t frames_in_contact = 0;
    double deepest = 0;
    for (const FrameRecord& f : loop.log) {
      frames_in_contact += f.contact_depth > 0;
      deepest = std::max(deepest, f.contact_depth);
    }
    contact = {{"pressure_stiffness_n_per_mm3", m.pressure_stiffness_n_per_mm3},
               {"sample_spacing", m.sample_spacing},
               {"distance_spacing", m.distance_spacing},
               {"skin", m.skin},
               {"part1_edge_points", m.part1_edge_points},
               {"part2_points", m.part2_points},
               {"build_s", run.contact_build_s},
               {"time_ms_p99", run.contact_ms},
               {"frames_in_contact", frames_in_contact},
               {"deepest", deepest}};
  }
  const nlohmann::json fit_stiffness = run.fit_stiffness ? stiffness_json(*run.fit_stiffness) : nullptr;
  nlohmann::json summary = loop_json(loop);
  summary.update({{"force_rate_bound",
                   {{"max_n_per_s", run.max_force_rate_n_per_s},
                    {"frames", loop.rate_limited_frames},
                    {"dissipated_j", loop.rate_limit_dissipated_j},
                    {"slewed_frames", loop.rate_slewed_frames},
                    {"slew_work_j", loop.rate_slew_work_j}}},
                  {"modes",
                   {{"tuned", tuning.chosen_modes},
                    {"start", run.start_modes},
                    {"final", loop.final_modes},
                    {"changes", mode_changes_json(loop.mode_changes)}}},
                  {"geometric_error_estimate", {{"force_n", spread(force_error)}, {"torque_nm", spread(torque_error)}}},
                  {"geometry_gain", run.geometry_gain},
                  {"rigid_contact", contact},
                  {"stiffness_at_fit", fit_stiffness},
                  {"force_scale", run.force_scale},
                  {"coupling",
                   {{"stiffness_n_per_m", run.coupling.stiffness},
                    {"rot_stiffness_nm_per_rad", run.coupling.rot_stiffness},
                    {"damping", run.coupling.damping},
                    {"rot_damping", run.coupling.rot_damping},
                    {"mass_kg", run.coupling.mass_kg},
                    {"inertia_kg_m2", run.coupling.inertia_kg_m2}}},
                  {"final_pose", pose_json<nlohmann::json>(fp)},
                  {"final_error",
                   {{"position", run.final_error.position},
                    {"angle_deg", run.final_error.angle_deg},
                    {"surface_deviation", run.surface_deviation},
                    {"surface_deviation_at",
                     {run.surface_deviation_at.x(), run.surface_deviation_at.y(), run.surface_deviation_at.z()}},
                    {"axial", run.axial_error},
                    {"lateral", run.lateral_error},
                    {"insertion_direction",
                     {run.insertion_direction.x(), run.insertion_direction.y(), run.insertion_direction.z()}}}},
                  {"final_force_n", {run.final_force.x(), run.final_force.y(), run.final_force.z()}},
                  {"tolerance", {{"position", run.position_tolerance}, {"angle_deg", run.angle_tolerance_deg}}},
                  {"assembled", run.evaluated ? nlohmann::json(run.assembled) : nlohmann::json(nullptr)},
                  {"verdict", session_verdict(run)},
                  {"wait", loop_wait_name(run.wait)},
                  {"priority",
                   {{"threads_raised", run.priority.threads},
                    {"realtime", run.priority.realtime},
                    {"failed", run.priority.failed},
                    {"reason", run.priority.reason}}}});
  return summary;
}

}  // namespace snapfit
