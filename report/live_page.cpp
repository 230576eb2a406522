#include "report/live_page.h"

#include "report/html_page.h"
#include "report/run_page.h"
#include "snapfit/job.h"
#include "snapfit/pose_json.h"

namespace snapfit {

std::string live_page_html(const JobResult& prepared, const LivePageInfo& info) {
  const Scene& scene = prepared.scene;
  // The meshes as they are: a live view redraws at the display's rate and colours no
  // contact, so it needs no refinement.
  const nlohmann::json data = {
      {"kind", "live"},
      {"title", "snapfit serve: " + scene.name},
      {"parts", {part_json(scene.part1.name, *prepared.part1.mesh), part_json(scene.part2.name, *prepared.part2.mesh)}},
      {"start_pose", pose_json<nlohmann::json>(scene.part2.pose)},
      {"units", scene.units},
      {"bridge_port", info.bridge_port},
      {"state_hz", info.state_hz}};
  return html_page("live_page", data["title"].get<std::string>(), data);
}

}  // namespace snapfit
