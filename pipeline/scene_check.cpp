// check_scene (include/snapfit/inspect.h): stage 1 of the pipeline (pipeline/assembly_pair.h)
// with no device, in public types.
#include "pipeline/scene_check.h"

#include "pipeline/assembly_pair.h"
#include "pipeline/part_mesh.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

PartCheck part_check(const PreparedPart& part) {
  PartCheck check;
  check.mesh = part.report;
  check.cad = part.cad;
  check.seconds = part.seconds;
  return check;
}

}  // namespace

SceneCheck scene_check_of(const PreparedParts& parts, const ComputePlan& plan) {
  SceneCheck check;
  check.part1 = part_check(parts.part1);
  check.part2 = part_check(parts.part2);
  check.plan = plan.lines;
  check.warnings = plan.warnings;
  return check;
}

SceneCheck check_scene(const Scene& scene) {
  const AssemblyPair pair = prepare_assembly_pair(scene);
  return scene_check_of(pair.parts, pair.plan);
}

PartGeometry part_geometry(const Scene& scene, int part) {
  if (part != 1 && part != 2) throw Error("part must be 1 or 2, not " + std::to_string(part));
  PartMesh built = build_part_mesh(part == 1 ? scene.part1 : scene.part2, scene);
  return std::move(built.mesh);
}

}  // namespace snapfit
