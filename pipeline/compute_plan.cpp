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
  plan.lines.push_back(plan.rotation
                           ? "spectra: both parts', and part 2's deconvolved for its exact rotation (6-DOF motion)"
                           : "spectra: both parts' (translation-only motion: part 2 never turns)");
  plan.lines.push_back(plan.rotation
                           ? "per frame: part 2's spectrum interpolated at the rotated frequencies (tricubic); "
                             "snapfit accuracy measures the exact-rotation product beside it"
                           : "per frame: phase sum over a precomputed product (translation-only motion, "
                             "no spectrum rotation)");
  if (plan.torque)
    plan.lines.push_back("torque: the derivative of the rendered energy under rotation (no extra fields)");
  std::string outputs = "energy";
  if (plan.force) outputs += ", force";
  if (plan.torque) outputs += ", torque";
  plan.lines.push_back("outputs per query: " + outputs);
  return plan;
}

void add_grid_warnings(ComputePlan& plan, const Scene& scene, double spacing) {
  if (!plan.skeletal_density || !(scene.descriptor.sigma < spacing)) return;
  plan.warnings.push_back("descriptor.sigma " + number(scene.descriptor.sigma) + " is below the grid spacing " +
                          number(spacing) +
                          ": the skeletal density's surface layer is under-resolved; a spacing of at most sigma "
                          "(or a larger sigma, which blurs the fit) resolves it");
}

}  // namespace snapfit
