#pragma once
// Text shared by `scene-check` and `run`: the scene, its parts and the compute plan.
#include <ostream>

#include "engine/compute_plan.h"
#include "io/scene.h"
#include "scheduler/prepare_parts.h"

namespace snapfit::cli {

void print_scene_summary(std::ostream& out, const Scene& scene, const PreparedParts& parts, const ComputePlan& plan);

}  // namespace snapfit::cli
