#include "report/accuracy_json.h"

namespace snapfit {

nlohmann::json strategy_accuracy_json(const StrategyAccuracy& s) {
  const bool torque = s.variant.torque;
  const auto per_output = [&](const double(&v)[3]) {
    return nlohmann::json{{"energy", v[0]}, {"force", v[1]}, {"torque", torque ? nlohmann::json(v[2]) : nullptr}};
  };
  nlohmann::json j = {{"strategy", s.name},
                      {"modes", s.modes},
                      {"fits_budget", s.fits},
                      {"frame_ms_p50", s.frame_ms_p50},
                      {"frame_ms_p99", s.frame_ms_p99},
                      {"energy_error", s.energy_error},
                      {"force_error", s.force_error},
                      {"torque_error", torque ? nlohmann::json(s.torque_error) : nullptr},
                      {"estimate_coverage", per_output(s.estimate_coverage)},
                      {"estimate_overestimate_median", per_output(s.estimate_ratio_median)}};
  if (s.variant.rotation == RotationMethod::exact_product) j["product_ms"] = s.product_ms;
  if (!s.turning.empty()) {
    nlohmann::json turning = nlohmann::json::array();
    for (const TurningAccuracy& t : s.turning)
      turning.push_back({{"deg_per_s", t.deg_per_s},
                         {"energy_error", t.energy_error},
                         {"force_error", t.force_error},
                         {"torque_error", torque ? nlohmann::json(t.torque_error) : nullptr},
                         {"at_rest",
                          {{"energy_error", t.at_rest_energy_error},
                           {"force_error", t.at_rest_force_error},
                           {"torque_error", torque ? nlohmann::json(t.at_rest_torque_error) : nullptr}}}});
    j["while_turning"] = turning;
  }
  return j;
}

}  // namespace snapfit
