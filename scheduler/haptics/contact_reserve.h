#pragma once
// The frame time the loop reserves for the rigid contact on this machine, before the
// query strategy and m' are chosen (AccuracyOptions::reserved_ms): the contact's p99
// near the fit (contact_cost_ms) rounded up to a tenth of a millisecond, measured once
// per machine, device and contact model and kept in the tuning folder
// (scheduler/modes/tuning_file.h), so that the strategy file chosen for it is found again on
// the next run instead of a noisy re-measurement asking for a new one.
#include <functional>
#include <string>

#include "engine/runtime/device.h"
#include "scheduler/haptics/rigid_contact.h"
#include "snapfit/scene.h"

namespace snapfit {

struct ContactReserve {
  double reserved_ms = 0;  // what the frame reserves
  double measured_ms = 0;  // the contact's p99 behind it (now, or when it was stored)
  bool from_file = false;
  std::string file;
};

// `device` names the machine (the loop's device info: its CPU for PoCL); `remeasure`
// measures even when a stored value matches. A value that cannot be saved is still used
// (`note` hears why).
ContactReserve contact_reserve(const Scene& scene, const Mesh& part1, const Mesh& part2,
                               std::shared_ptr<const RigidContactModel> model, const DeviceInfo& device,
                               bool remeasure, const std::function<void(const std::string&)>& note = nullptr);

// measured_ms rounded up to a tenth of a millisecond (0 for 0).
double rounded_reserve_ms(double measured_ms);

}  // namespace snapfit
