#pragma once
// A scene's prepared parts and compute plan as the public SceneCheck
// (include/snapfit/inspect.h), for the reports of every command that builds them.
#include "pipeline/compute_plan.h"
#include "pipeline/prepare_parts.h"
#include "snapfit/inspect.h"

namespace snapfit {

SceneCheck scene_check_of(const PreparedParts& parts, const ComputePlan& plan);

}  // namespace snapfit
