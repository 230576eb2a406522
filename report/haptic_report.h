#pragma once
// The haptic part of `snapfit run`'s report folder: the loop's per-frame log (loop.csv)
// and its summary as JSON; the tuning sweep as a chart.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "report/chart_spec.h"
#include "snapfit/job_facts.h"
#include "snapfit/tuning.h"

namespace snapfit {

// Writes the session's loop.csv into `out`; returns the JSON summary of the run.
nlohmann::json write_haptic_report(const std::filesystem::path& out, const SessionFacts& run, const LoopReport& loop,
                                   const TuningResult& tuning);

// The rendered stiffness at a pose (include/snapfit/job_facts.h) as JSON: N/mm along
// and N m/degree about +-x, +-y, +-z, beside the coupling's.
nlohmann::json stiffness_json(const RenderedStiffness& stiffness);

// The tuning sweep as a chart: p50 and p99 against m', the budget, the chosen m'.
Chart tuning_chart(const TuningResult& tuning, const std::string& device_name);

}  // namespace snapfit
