#pragma once
// The haptic part of `snapfit run`'s report folder: the loop's per-frame log (loop.csv)
// and its summary as JSON; the tuning sweep as a chart and as a table.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "report/chart_spec.h"
#include "scheduler/assembly_session.h"
#include "scheduler/mode_tuning.h"

namespace snapfit {

// Writes loop.csv into `out`; returns the JSON summary of the run.
nlohmann::json write_haptic_report(const std::filesystem::path& out, const SessionResult& run,
                                   const TuningResult& tuning);

// The rendered stiffness at a pose (scheduler/rendered_wrench.h) as JSON: N/mm along
// and N m/degree about +-x, +-y, +-z, beside the coupling's.
nlohmann::json stiffness_json(const RenderedStiffness& stiffness);

// "assembled", "not assembled", or "not evaluated (no assembled pose)".
std::string session_verdict(const SessionResult& run);

// The end of the run in words: the signed axial and the lateral error, the angle and the
// force still sent, e.g. "axial +0.375 mm (past the fit), lateral 0.021 mm, 0.04 deg;
// 0.30 N sent".
std::string final_error_text(const SessionResult& run, const std::string& units);

// The tuning sweep as a chart: p50 and p99 against m', the budget, the chosen m'.
Chart tuning_chart(const TuningResult& tuning, const std::string& device_name);

// The tuning table for people: one line per m' level.
std::string tuning_table(const TuningResult& tuning);

}  // namespace snapfit
