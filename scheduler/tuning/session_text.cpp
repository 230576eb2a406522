// tuning_table (include/snapfit/tuning.h), session_verdict and final_error_text
// (include/snapfit/job_facts.h): text for people about a tuning sweep and a session.
#include "snapfit/job_facts.h"
#include "snapfit/tuning.h"

#include <cstdio>
#include <iomanip>
#include <sstream>

namespace snapfit {

std::string tuning_table(const TuningResult& t) {
  std::ostringstream s;
  char row[160];
  std::snprintf(row, sizeof row, "  %9s %9s %9s %9s %10s\n", "m'", "p50 ms", "p99 ms", "max ms", "model ms");
  s << row;
  for (const TimingPoint& p : t.points) {
    std::snprintf(row, sizeof row, "  %9zu %9.3f %9.3f %9.3f %10.3f%s\n", p.modes, p.p50_ms, p.p99_ms, p.max_ms,
                  t.model.predict_ms(p.modes), p.modes == t.chosen_modes ? "  <- chosen" : "");
    s << row;
  }
  std::snprintf(row, sizeof row, "  target p99 <= %.3f ms (budget %.3f ms, margin %.0f%%): m' = %zu%s\n", t.target_ms(),
                t.budget_ms, 100 * t.margin, t.chosen_modes,
                t.fits ? "" : " (the budget is NOT met even at the smallest level)");
  s << row;
  return s.str();
}

std::string session_verdict(const SessionFacts& run) {
  if (!run.evaluated) return "not evaluated (no assembled pose)";
  return run.assembled ? "assembled" : "not assembled";
}

std::string final_error_text(const SessionFacts& run, const std::string& units) {
  std::ostringstream t;
  t << std::showpos << std::setprecision(3) << "axial " << run.axial_error << std::noshowpos << " " << units << " ("
    << (run.axial_error > 0 ? "past" : "short of") << (run.evaluated ? " the fit" : " the last keyframe")
    << "), lateral " << run.lateral_error << " " << units << ", " << run.final_error.angle_deg << " deg; "
    << run.final_force.norm() << " N sent";
  return t.str();
}

}  // namespace snapfit
