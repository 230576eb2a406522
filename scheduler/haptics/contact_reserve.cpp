#include "scheduler/haptics/contact_reserve.h"

#include <cmath>
#include <sstream>

#include "core/hash.h"
#include "mesh/mesh_hash.h"
#include "scheduler/haptics/haptic_setup.h"
#include "scheduler/haptics/parallel_contact.h"
#include "scheduler/modes/tuning_file.h"
#include "snapfit/error.h"

namespace snapfit {

// Changes with the contact's evaluation code, so that timings of older code are not reused.
constexpr const char* kContactEvaluation = "rigid contact evaluation 3";

double rounded_reserve_ms(double measured_ms) {
  if (!(measured_ms > 0)) return 0;
  return std::ceil(measured_ms * 10.0 - 1e-9) / 10.0;
}

ContactReserve contact_reserve(const Scene& scene, const Mesh& part1, const Mesh& part2,
                               std::shared_ptr<const RigidContactModel> model, const DeviceInfo& device,
                               bool remeasure, const std::function<void(const std::string&)>& note) {
  ContactReserve r;
  if (!model) return r;
  TuningKey key;
  key.platform = device.platform_name + " " + device.platform_version;
  key.device = device.name;
  key.driver = device.driver_version;
  key.variant = std::string(kContactEvaluation) + " on " + std::to_string(contact_threads_for(*model)) + " threads";
  std::ostringstream features;
  features << "part1 " << hex64(mesh_hash(part1)) << " part2 " << hex64(mesh_hash(part2)) << " points "
           << model->part1_samples.points.size() << "+" << model->part2_samples.points.size() << " distance "
           << model->part1_distance.fine_spacing() << " pose " << gain_reference_pose(scene).translation.transpose();
  key.scene_features = features.str();
  key.budget_ms = scene.frame_budget_ms;
  key.margin = 0;
  r.file = tuning_file_path(key);
  if (!remeasure)
    if (std::optional<TuningResult> stored = load_tuning(key); stored && !stored->points.empty()) {
      r.measured_ms = stored->points.front().p99_ms;
      r.reserved_ms = rounded_reserve_ms(r.measured_ms);
      r.from_file = true;
      return r;
    }
  r.measured_ms = contact_cost_ms(contact_evaluator(model), *model, scene);
  r.reserved_ms = rounded_reserve_ms(r.measured_ms);
  TuningResult timing;
  timing.points.push_back(TimingPoint{model->part1_samples.points.size() + model->part2_samples.points.size(),
                                      r.measured_ms, r.measured_ms, r.measured_ms, 1});
  timing.chosen_modes = timing.points.front().modes;
  timing.budget_ms = scene.frame_budget_ms;
  try {
    save_tuning(key, timing);
  } catch (const Error& e) {
    if (note) note(std::string("the contact's time was not saved: ") + e.what());
  }
  return r;
}

}  // namespace snapfit
