#pragma once
// The main job's text for people: the measured strategies with the chosen one, and the
// scripted session's summary (frame times, misses, m' changes, the final pose error).
#include <string>

#include "scheduler/haptics/assembly_session.h"
#include "scheduler/tuning/query_strategy.h"
#include "snapfit/scene.h"

namespace snapfit {

// Where the strategies came from and one line per strategy: m', p99, errors, fit.
std::string strategies_text(const StrategyChoice& choice);

// The loop's rate and frame times, its m' changes, and the verdict on the final pose.
std::string session_text(const Scene& scene, const SessionResult& session);

}  // namespace snapfit
