#include "pipeline/compute_plan.h"

#include <sstream>

namespace snapfit {
namespace {

std::string number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

}  // namespace

ComputePlan plan_computation(const Scene& scene) {
  ComputePlan plan;
  plan.skeletal_density = scene.descriptor.kind == DescriptorKind::skeletal_density;
  plan.rotation = scene.motion == Motion::six_dof;
  plan.force = scene.outputs.force;
  plan.torque = scene.outputs.torque && plan.rotation;
  plan.torque_fields = plan.torque;

  if (plan.skeletal_density) {
    plan.lines.push_back(
        "fields: winding number, signed distance and skeletal density (sigma " + number(scene.descriptor.sigma) +
        ") for both parts, affinity rho = i*lambda*s "
        "(lambda_in " +
        number(scene.descriptor.lambda_in) + ", lambda_out " + number(scene.descriptor.lambda_out) + ")");
  } else {
    plan.lines.push_back(
        "fields: winding number (indicator) only: the scene asks for collision response, "
        "so no signed distance or skeletal density is computed");
  }
  plan.lines.push_back(plan.torque_fields
                           ? "torque fields: q*rho2 (3 components) for part 2, because the scene needs torque"
                           : "torque fields: none, the scene does not need torque");
  plan.lines.push_back(plan.rotation ? "per frame: rotate part 2's spectrum (6-DOF motion), multiply, reduce"
                                     : "per frame: phase sum over a precomputed product (translation-only motion, "
                                       "no spectrum rotation)");
  std::string outputs = "energy";
  if (plan.force) outputs += ", force";
  if (plan.torque) outputs += ", torque";
  plan.lines.push_back("outputs per query: " + outputs);
  return plan;
}

}  // namespace snapfit
