#include "report/search_report.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "report/chart_spec.h"
#include "snapfit/export.h"
#include "snapfit/pose_json.h"

namespace snapfit {
namespace {

constexpr double kDeg = M_PI / 180.0;

nlohmann::json refined_json(const RefinedPose& r) {
  if (!r.error.empty()) return {{"error", r.error}};
  nlohmann::json by_energy = pose_json<nlohmann::json>(r.energy_minimum);
  by_energy["energy"] = r.energy_minimum_energy;
  by_energy["queries"] = r.queries;
  nlohmann::json j = by_energy;
  j["by"] = "energy";
  if (r.rendered) {
    j = pose_json<nlohmann::json>(r.pose);
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

std::string search_lines(const SearchResult& result) {
  std::ostringstream lines;
  for (std::size_t k = 0; k < result.top.size(); ++k) {
    const FoundPose& found = result.top[k];
    nlohmann::json line = pose_json<nlohmann::json>(found.pose);
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
    const Eigen::AngleAxisd aa(result.rotations[r]);
    const bool turned = std::abs(aa.angle()) > 1e-12;
    const Eigen::Vector3d axis = turned ? aa.axis() : Eigen::Vector3d::UnitZ();
    char line[256];
    std::snprintf(line, sizeof line, "%zu,%.9g,%.9g,%.9g,%.9g,%.9g\n", r, axis.x(), axis.y(), axis.z(),
                  turned ? aa.angle() / kDeg : 0.0, result.best_energy[r]);
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
