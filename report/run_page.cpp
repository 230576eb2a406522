#include "report/run_page.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "report/chart_spec.h"
#include "report/haptic_report.h"
#include "report/html_page.h"
#include "report/loop_display.h"
#include "report/page_encoding.h"
#include "report/part_contact.h"
#include "report/strategy_chart.h"
#include "snapfit/accuracy.h"
#include "snapfit/error.h"
#include "snapfit/mesh.h"

namespace snapfit {
namespace {

std::string short_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

// What m' the loop rendered: the most frequent and the frame-weighted mean over its
// frames, where it started and ended, and how often it changed.
nlohmann::json rendered_modes_json(const LoopReport& loop) {
  if (loop.log.empty()) return nullptr;
  std::map<std::size_t, std::size_t> frames_at;
  double sum = 0;
  for (const FrameRecord& f : loop.log) ++frames_at[f.modes], sum += double(f.modes);
  const auto most = std::max_element(frames_at.begin(), frames_at.end(),
                                     [](const auto& a, const auto& b) { return a.second < b.second; });
  return {
      {"most_frequent", most->first},          {"most_frequent_share", double(most->second) / double(loop.log.size())},
      {"mean", sum / double(loop.log.size())}, {"start", loop.log.front().modes},
      {"final", loop.log.back().modes},        {"changes", loop.mode_changes.size()}};
}

// The strategies measured for this scene, one row each, beside their chart: what the
// strategy card's one line sums up.
nlohmann::json strategy_table_json(const JobResult& run) {
  if (!run.strategies || run.strategies->strategies.size() < 2) return nullptr;
  nlohmann::json rows = nlohmann::json::array();
  const std::vector<StrategyAccuracy>& all = run.strategies->strategies;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const StrategyAccuracy& s = all[i];
    rows.push_back({{"strategy", s.name},
                    {"label", strategy_short_name(s.variant)},
                    {"modes", s.modes},
                    {"frame_ms_p99", s.frame_ms_p99},
                    {"energy_error", s.energy_error},
                    {"force_error", s.variant.force ? nlohmann::json(s.force_error) : nlohmann::json(nullptr)},
                    {"torque_error", s.variant.torque ? nlohmann::json(s.torque_error) : nlohmann::json(nullptr)},
                    {"fits_budget", s.fits},
                    {"lowest_error_that_fits", i == run.strategies->best}});
  }
  return rows;
}

nlohmann::json summary_json(const JobResult& run) {
  const Scene& scene = run.scene;
  nlohmann::json s = {{"scene", scene.name},
                      {"scene_file", scene.source_path},
                      {"units", scene.units},
                      {"device", run.device},
                      {"loop_device", run.loop_device},
                      {"method", method_name(scene.method)},
                      {"modes", run.tuning.chosen_modes},
                      {"modes_source", run.vps                  ? "none: Voxmap PointShell"
                                       : run.tuning_key.empty() ? "fixed by --modes"
                                                                : "tuned for this device"},
                      {"seconds", run.seconds},
                      {"frames", nullptr},
                      {"misses", nullptr},
                      {"miss_rate", nullptr},
                      {"assembled", nullptr},
                      {"final_error", nullptr},
                      {"verdict", nullptr},
                      {"modes_rendered", nullptr},
                      {"stiffness_at_fit", nullptr},
                      {"query_strategy", nullptr}};
  if (!run.strategy.empty())
    s["query_strategy"] = {{"name", run.strategy},
                           {"label", run.strategy_label},
                           {"chosen_by", run.strategy_chosen_by},
                           {"why", run.strategies ? nlohmann::json(run.strategies->why) : nlohmann::json(nullptr)}};
  if (run.session && run.loop) {
    const LoopReport& loop = *run.loop;
    s["frames"] = loop.frames;
    s["misses"] = loop.misses;
    s["miss_rate"] = loop.miss_rate();
    s["assembled"] = run.session->evaluated ? nlohmann::json(run.session->assembled) : nlohmann::json(nullptr);
    s["verdict"] = session_verdict(*run.session);
    s["final_error"] = {{"position", run.session->final_error.position},
                        {"angle_deg", run.session->final_error.angle_deg},
                        {"surface_deviation", run.session->surface_deviation},
                        {"axial", run.session->axial_error},
                        {"lateral", run.session->lateral_error},
                        {"final_force_n", run.session->final_force.norm()},
                        {"text", final_error_text(*run.session, scene.units)}};
    s["modes_rendered"] = rendered_modes_json(loop);
    if (run.session->fit_stiffness) s["stiffness_at_fit"] = stiffness_json(*run.session->fit_stiffness);
  }
  return s;
}

// Playback: part 2's pose, the wrench sent to the device, energy and m' at evenly spaced
// frames; inside-flags of both parts' triangles at as many of them as contact_bits allows.
nlohmann::json playback_json(const JobResult& run, const std::vector<Mesh>& shown, const RunPageLimits& limits) {
  const LoopReport& loop = *run.loop;
  const std::vector<std::size_t> frames =
      evenly_spaced_frames(loop.log.size(), std::max<std::size_t>(2, limits.playback_frames));
  std::vector<double> time, position, quaternion, force, torque, energy, modes;
  double force_max = 0, torque_max = 0;
  for (const FrameRecord& f : loop.log) {
    force_max = std::max(force_max, f.sent.force.norm());
    torque_max = std::max(torque_max, f.sent.torque.norm());
  }
  for (std::size_t i : frames) {
    const FrameRecord& f = loop.log[i];
    const Eigen::Quaterniond q = f.part.rotation.normalized();
    time.push_back(f.time_s);
    position.insert(position.end(), {f.part.translation.x(), f.part.translation.y(), f.part.translation.z()});
    quaternion.insert(quaternion.end(), {q.w(), q.x(), q.y(), q.z()});
    force.insert(force.end(), {f.sent.force.x(), f.sent.force.y(), f.sent.force.z()});
    torque.insert(torque.end(), {f.sent.torque.x(), f.sent.torque.y(), f.sent.torque.z()});
    energy.push_back(f.energy);
    modes.push_back(static_cast<double>(f.modes));
  }

  // Contact at a subset of the playback frames, evenly spaced among them.
  const std::vector<Eigen::Vector3d> centroids[2] = {triangle_centroids(shown[0]), triangle_centroids(shown[1])};
  const bool have_fields = run.part1.fields && run.part2.fields && !run.part1.fields->fields.winding.empty() &&
                           !run.part2.fields->fields.winding.empty();
  PartVolume volumes[2];
  if (have_fields)
    for (int i = 0; i < 2; ++i) {
      const DescriptorFields& f = run.part(i + 1).fields->fields;
      volumes[i] = {&f.grid, &f.winding};
    }
  const std::size_t bits_a_frame = std::max<std::size_t>(1, centroids[0].size() + centroids[1].size());
  const std::size_t contact_frames = std::min(frames.size(), limits.contact_bits / bits_a_frame);
  nlohmann::json contact = nullptr;
  if (contact_frames >= 1 && have_fields) {
    std::vector<std::size_t> picked;
    std::vector<unsigned char> bytes[2];
    for (std::size_t k : evenly_spaced_frames(frames.size(), std::max<std::size_t>(2, contact_frames))) {
      if (picked.size() == contact_frames) break;
      picked.push_back(k);
      const Pose& part2 = loop.log[frames[k]].part;
      // Part 1's triangles into part 2's frame, part 2's into part 1's.
      const std::vector<std::uint8_t> in1 = points_inside(centroids[0], part2.inverse(), volumes[1]);
      const std::vector<std::uint8_t> in2 = points_inside(centroids[1], part2, volumes[0]);
      bytes[0].insert(bytes[0].end(), in1.begin(), in1.end());
      bytes[1].insert(bytes[1].end(), in2.begin(), in2.end());
    }
    contact = {{"frames", picked},
               {"bytes", {(centroids[0].size() + 7) / 8, (centroids[1].size() + 7) / 8}},
               {"part1", base64_encode(bytes[0].data(), bytes[0].size())},
               {"part2", base64_encode(bytes[1].data(), bytes[1].size())}};
  }
  return {{"frames_total", loop.log.size()},
          {"time", float32_base64(time)},
          {"position", float32_base64(position)},
          {"quaternion", float32_base64(quaternion)},
          {"force", float32_base64(force)},
          {"torque", float32_base64(torque)},
          {"energy", float32_base64(energy)},
          {"modes", float32_base64(modes)},
          {"force_max", force_max},
          {"torque_max", torque_max},
          {"contact", contact}};
}

Chart time_chart(const std::string& title, const std::string& y_label, const Envelope& e,
                 const std::vector<std::pair<std::size_t, std::string>>& series) {
  Chart c;
  c.title = title;
  c.x_label = "time (s)";
  c.y_label = y_label;
  for (const auto& [index, label] : series)
    c.series.push_back(Series{label, e.time, e.values[index], Series::Style::line, ""});
  return c;
}

// The loop's time series, every frame or min/max envelopes of buckets of frames.
nlohmann::json timeline_json(const JobResult& run, const RunPageLimits& limits) {
  const Scene& scene = run.scene;
  const SessionFacts& session = *run.session;
  const LoopReport& loop = *run.loop;
  enum { energy, geo_force, sent_force, geo_torque, sent_torque, position_error, angle_error, modes, frame_ms, count };
  std::vector<double> time;
  std::vector<std::vector<double>> v(count);
  for (const FrameRecord& f : loop.log) {
    time.push_back(f.time_s);
    const PoseError e = pose_error(f.part, session.target);
    for (auto [k, value] : {std::pair{energy, f.energy},
                            {geo_force, f.geometric.force.norm()},
                            {sent_force, f.sent.force.norm()},
                            {geo_torque, f.geometric.torque.norm()},
                            {sent_torque, f.sent.torque.norm()},
                            {position_error, e.position},
                            {angle_error, e.angle_deg},
                            {modes, double(f.modes)},
                            {frame_ms, f.frame_ms}})
      v[k].push_back(value);
  }
  const Envelope e = envelope(time, v, std::max<std::size_t>(2, limits.chart_points));
  std::vector<Chart> charts;
  // E = -Re of the overlap integral of two dimensionless affinities: a volume.
  charts.push_back(
      time_chart("Geometric energy at the part's pose", "energy (" + scene.units + "^3)", e, {{energy, "energy"}}));
  charts.push_back(time_chart("Force", "N", e, {{geo_force, "|geometric force|"}, {sent_force, "|force to device|"}}));
  if (scene.outputs.torque)
    charts.push_back(
        time_chart("Torque", "N m", e, {{geo_torque, "|geometric torque|"}, {sent_torque, "|torque to device|"}}));
  const std::string against = session.evaluated ? "the assembled pose" : "the last keyframe";
  Chart position = time_chart("Position error against " + against, scene.units, e,
                              {{position_error, "position error (" + scene.units + ")"}});
  position.hlines.push_back(HLine{session.position_tolerance, "tolerance"});
  charts.push_back(position);
  Chart angle = time_chart("Angle error against " + against, "deg", e, {{angle_error, "angle error (deg)"}});
  angle.hlines.push_back(HLine{session.angle_tolerance_deg, "tolerance"});
  charts.push_back(angle);
  if (!run.vps) charts.push_back(time_chart("m' (Fourier modes) in the loop", "m'", e, {{modes, "m'"}}));
  Chart frames = time_chart("Frame time", "ms", e, {{frame_ms, "frame time"}});
  frames.hlines.push_back(HLine{scene.frame_budget_ms, "budget"});
  Series missed{"missed frames", {}, {}, Series::Style::points, "#d62728"};
  for (const FrameRecord& f : loop.log)
    if (f.missed && missed.x.size() < limits.missed_points) {
      missed.x.push_back(f.time_s);
      missed.y.push_back(f.frame_ms);
    }
  if (!missed.x.empty()) frames.series.push_back(missed);
  charts.push_back(frames);

  nlohmann::json specs = nlohmann::json::array();
  for (const Chart& c : charts) specs.push_back(chart_json(c));
  const std::string shown = e.bucket == 1 ? "Every frame of the " + std::to_string(loop.log.size()) + " is drawn."
                                          : "The run's " + std::to_string(loop.log.size()) +
                                                " frames are drawn in buckets of " + std::to_string(e.bucket) +
                                                ": each bucket as its minimum and maximum. loop.csv has every frame.";
  return {{"frames_total", loop.log.size()},
          {"bucket", e.bucket},
          {"notes", {shown + " Click a chart to move the playback there."}},
          {"charts", specs}};
}

}  // namespace

nlohmann::json part_json(const std::string& name, const Mesh& mesh) {
  std::vector<float> positions;
  positions.reserve(9 * mesh.triangles.size());
  for (const Eigen::Vector3i& t : mesh.triangles)
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) positions.push_back(static_cast<float>(mesh.vertices[t[k]][a]));
  return {{"name", name}, {"triangles", mesh.triangles.size()}, {"positions", float32_base64(positions)}};
}

Mesh display_mesh(const Mesh& mesh, double spacing, std::size_t max_triangles) {
  if (mesh.triangles.size() >= max_triangles || !(spacing > 0)) return mesh;
  for (double radius = spacing; radius < 1e6 * spacing; radius *= 2) {
    try {
      return refine_triangles(mesh, radius, max_triangles);
    } catch (const Error&) {
      // too many pieces at this radius: try a coarser one
    }
  }
  return mesh;
}

nlohmann::json run_page_data(const JobResult& run, const std::vector<PageFigure>& figures,
                             const RunPageLimits& limits) {
  const Scene& scene = run.scene;
  const std::vector<Mesh> shown = {display_mesh(*run.part1.mesh, run.spacing, limits.display_triangles),
                                   display_mesh(*run.part2.mesh, run.spacing, limits.display_triangles)};
  nlohmann::json slices = nlohmann::json::array();
  for (const PageFigure& f : figures)
    slices.push_back({{"caption", f.caption}, {"png", base64_encode(f.png.data(), f.png.size())}});
  std::vector<std::string> notes = {
      "Red triangles: their centre lies inside the other part at that moment, by the other part's winding-number "
      "field on its grid (spacing " +
      short_number(run.spacing) + " " + scene.units +
      ", trilinear, above 1/2), so within about one spacing of a surface the colouring may go either way."};
  nlohmann::json data = {
      {"kind", "run"},
      {"title", "snapfit run: " + scene.name},
      {"summary", summary_json(run)},
      {"parts", {part_json(scene.part1.name, shown[0]), part_json(scene.part2.name, shown[1])}},
      {"start_pose", pose_json<nlohmann::json>(scene.part2.pose)},
      {"playback", nullptr},
      {"timeline", nullptr},
      {"tuning_chart",
       run.tuning_key.empty() ? nlohmann::json(nullptr) : chart_json(tuning_chart(run.tuning, run.loop_device))},
      {"strategy_chart", run.strategies && run.strategies->strategies.size() > 1
                             ? chart_json(strategy_chart(run.strategies->strategies, scene.frame_budget_ms))
                             : nlohmann::json(nullptr)},
      {"strategy_table", strategy_table_json(run)},
      {"slices", slices},
      {"notes", notes}};
  if (run.session && run.loop && !run.loop->log.empty()) {
    data["playback"] = playback_json(run, shown, limits);
    data["timeline"] = timeline_json(run, limits);
    const LoopReport& loop = *run.loop;
    if (!loop.frame_ms.empty()) {
      Chart hist = histogram_chart("Frame time, " + std::to_string(loop.frames) + " frames at " +
                                       std::to_string(static_cast<int>(loop.rate_hz)) + " Hz",
                                   "frame time (ms)", loop.frame_ms, 60, true);
      data["frame_time_histogram"] = chart_json(hist);
    }
  }
  return data;
}

void write_run_page(const std::string& path, const JobResult& run, const std::vector<PageFigure>& figures,
                    const RunPageLimits& limits) {
  const nlohmann::json data = run_page_data(run, figures, limits);
  write_html_page(path, "run_report", data["title"].get<std::string>(), data);
}

}  // namespace snapfit
