#include "report/search_report.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "io/atomic_write.h"
#include "report/chart_spec.h"

namespace snapfit {
namespace {

constexpr double kDeg = M_PI / 180.0;

nlohmann::json refined_json(const RefinedPose& r) {
  if (!r.error.empty()) return {{"error", r.error}};
  nlohmann::json by_energy = search_pose_json(r.energy_minimum);
  by_energy["energy"] = r.energy_minimum_energy;
  by_energy["queries"] = r.queries;
  nlohmann::json j = by_energy;
  j["by"] = "energy";
  if (r.rendered) {
    j = search_pose_json(r.pose);
    j["by"] = "rendered potential (energy x gain + rigid contact)";
    j["energy"] = r.energy;
    j["potential_j"] = r.potential_j;
    j["newton_steps"] = r.newton_steps;
    j["energy_minimum"] = by_energy;
  }
  j["modes"] = r.modes;
  return j;
}

}  // namespace

nlohmann::json search_pose_json(const Pose& pose) {
  const Eigen::AngleAxisd aa(pose.rotation);
  const bool turned = std::abs(aa.angle()) > 1e-12;
  const Eigen::Vector3d axis = turned ? aa.axis() : Eigen::Vector3d::UnitZ();
  return {{"position", {pose.translation.x(), pose.translation.y(), pose.translation.z()}},
          {"rotation_axis", {axis.x(), axis.y(), axis.z()}},
          {"rotation_deg", turned ? aa.angle() / kDeg : 0.0}};
}

std::string search_lines(const SearchResult& result) {
  std::ostringstream lines;
  for (std::size_t k = 0; k < result.top.size(); ++k) {
    const FoundPose& found = result.top[k];
    nlohmann::json line = search_pose_json(found.pose);
    line["rank"] = k + 1;
    line["energy"] = found.energy;
    line["map_fft"] = result.map_fft;
    line["map_batch"] = result.map_batch;
    line["refined"] = refined_json(found.refined);
    lines << line.dump() << "\n";
  }
  return lines.str();
}

void write_search_report(const std::string& dir, const SearchResult& result, const std::string& lines,
                         const std::string& title) {
  std::filesystem::create_directories(dir);
  std::ostringstream csv;
  csv << "rotation,axis_x,axis_y,axis_z,angle_deg,best_energy\n";
  Series series;
  series.label = "lowest E of the rotation's map";
  series.style = Series::Style::points;
  for (std::size_t r = 0; r < result.best_energy.size(); ++r) {
    const nlohmann::json p = search_pose_json(Pose{result.rotations[r], Eigen::Vector3d::Zero()});
    char line[256];
    std::snprintf(line, sizeof line, "%zu,%.9g,%.9g,%.9g,%.9g,%.9g\n", r, double(p["rotation_axis"][0]),
                  double(p["rotation_axis"][1]), double(p["rotation_axis"][2]), double(p["rotation_deg"]),
                  result.best_energy[r]);
    csv << line;
    series.x.push_back(double(r));
    series.y.push_back(result.best_energy[r]);
  }
  write_text_file(dir + "/best_per_rotation.csv", csv.str());
  Chart chart;
  chart.title = "Best energy per rotation";
  chart.x_label = "rotation index (base cell, then turn about it)";
  chart.y_label = "lowest E over translations";
  chart.series.push_back(series);
  for (std::size_t k = 0; k < result.top.size(); ++k)
    chart.markers.push_back({double(result.top[k].rotation), result.top[k].energy, "#" + std::to_string(k + 1)});
  write_chart_page(dir + "/search.html", "snapfit search: " + title,
                   {std::to_string(result.best_energy.size()) + " rotations; best_per_rotation.csv holds the values"},
                   {chart});
  write_text_file(dir + "/top.jsonl", lines);
}

}  // namespace snapfit
