#pragma once
// Text shared by `scene-check` and `run`: the scene, its parts and the compute plan.
#include <ostream>

#include "pipeline/compute_plan.h"
#include "pipeline/part_fields.h"
#include "pipeline/prepare_parts.h"
#include "snapfit/inspect.h"
#include "snapfit/scene.h"

namespace snapfit {

void print_scene_summary(std::ostream& out, const Scene& scene, const SceneCheck& check);
void print_scene_summary(std::ostream& out, const Scene& scene, const PreparedParts& parts, const ComputePlan& plan);

// Where a part's fields came from, how long they took, and their error bounds.
void print_fields_summary(std::ostream& out, const PartFieldsResult& result);

}  // namespace snapfit
