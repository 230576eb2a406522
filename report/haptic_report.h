#pragma once
// The haptic part of `snapfit run`'s report folder: the loop's per-frame log (CSV),
// charts (frame-time histogram, energy, force and torque, pose error against the
// assembled pose), and the summary as JSON.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "report/plot.h"
#include "scheduler/assembly_session.h"
#include "scheduler/auto_tune.h"
#include "snapfit/scene.h"

namespace snapfit {

// Writes loop.csv, frame_times.png, energy.png, force_torque.png, pose_error.png and
// tuning.png into `out`; returns the JSON summary of the run.
nlohmann::json write_haptic_report(const std::filesystem::path& out, const Scene& scene, const SessionResult& run,
                                   const TuningResult& tuning);

// The tuning sweep as a chart: p50 and p99 against m', the budget, the chosen m'.
Chart tuning_chart(const TuningResult& tuning, const std::string& device_name);

// The tuning table for people: one line per m' level.
std::string tuning_table(const TuningResult& tuning);

}  // namespace snapfit
