#pragma once
// One strategy of an accuracy report (scheduler/tuning/accuracy.h) as the JSON object that
// `snapfit accuracy` prints and perf/bench_accuracy writes.
#include <nlohmann/json.hpp>

#include "snapfit/accuracy.h"

namespace snapfit {

// strategy, modes, fits_budget, frame_ms_p50/p99, energy/force/torque_error (torque null
// without torque), the error estimate's coverage and median overestimate per output,
// and product_ms for the exact product.
nlohmann::json strategy_accuracy_json(const StrategyAccuracy& s);

}  // namespace snapfit
