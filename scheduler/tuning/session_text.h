#pragma once
// Text for people about a tuning sweep and a scripted session: what `snapfit run` and
// `snapfit tune` print, and the report's verdict lines.
#include <string>

#include "scheduler/haptics/assembly_session.h"
#include "snapfit/tuning.h"

namespace snapfit {

// The tuning table: one line per m' level, then the target and the chosen m'.
std::string tuning_table(const TuningResult& tuning);

// "assembled", "not assembled", or "not evaluated (no assembled pose)".
std::string session_verdict(const SessionResult& run);

// The end of the run in words: the signed axial and the lateral error, the angle and the
// force still sent, e.g. "axial +0.375 mm (past the fit), lateral 0.021 mm, 0.04 deg;
// 0.30 N sent".
std::string final_error_text(const SessionResult& run, const std::string& units);

}  // namespace snapfit
