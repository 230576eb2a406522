#include "jobs/job_text.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "core/quantile.h"
#include "snapfit/job_facts.h"
#include "snapfit/tuning.h"

namespace snapfit {

std::string strategies_text(const StrategyChoice& choice) {
  const std::vector<StrategyAccuracy>& all = choice.report.strategies;
  int width = 8;
  for (const StrategyAccuracy& s : all) width = std::max(width, static_cast<int>(s.name.size()));
  std::ostringstream out;
  out << "    " << (choice.from_file ? "from the strategy file " : "measured and saved to ") << choice.path << "\n";
  char line[512];
  std::snprintf(line, sizeof line, "    %-*s %9s %8s %8s %8s %8s\n", width, "strategy", "m'", "p99 ms", "energy",
                "force", "torque");
  out << line;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const StrategyAccuracy& s = all[i];
    std::snprintf(line, sizeof line, "    %-*s %9zu %8.3f %7.2f%% %7.2f%% %7.2f%%%s%s\n", width, s.name.c_str(),
                  s.modes, s.frame_ms_p99, 100 * s.energy_error, 100 * s.force_error, 100 * s.torque_error,
                  s.fits ? "" : "  does not fit", i == choice.report.best ? "  <- chosen" : "");
    out << line;
  }
  if (!all.empty()) out << "    chosen: " << all[choice.report.best].name << ": " << choice.report.why << "\n";
  return out.str();
}

std::string session_text(const Scene& scene, const SessionResult& session) {
  const LoopReport& loop = session.loop;
  std::ostringstream out;
  if (session.contact)
    out << "    rigid contact: built in " << session.contact_build_s << " s, " << session.contact_ms
        << " ms a frame (p99 near the fit) left out of the query's budget: the loop starts at m' "
        << session.start_modes << "\n";
  out << "    " << loop.frames << " frames, measured " << loop.measured_rate_hz << " Hz; frame time p50 "
      << quantile(loop.frame_ms, 0.5) << " ms, p99 " << quantile(loop.frame_ms, 0.99) << " ms, max "
      << quantile(loop.frame_ms, 1.0) << " ms; " << loop.misses << " misses (" << 100 * loop.miss_rate() << " %; "
      << loop.late_wakeup_misses << " late wake-ups, " << loop.stall_misses << " stalls), " << loop.mode_changes.size()
      << " m' changes; threads: " << session.priority.describe() << "\n";
  if (loop.out_of_region_frames > 0)
    out << "    " << loop.out_of_region_frames
        << " frames with part 2 outside the region part 1's fields cover (grid.region): the engine's wrench was "
           "not rendered there\n";
  for (const ModeChange& c : loop.mode_changes)
    out << "      t = " << c.time_s << " s: m' " << c.from << " -> " << c.to << " (" << c.reason << ")\n";
  out << "    final pose error " << session.final_error.position << " " << scene.units << ", "
      << session.final_error.angle_deg << " deg, surface " << session.surface_deviation << " " << scene.units
      << " off (tolerance " << session.position_tolerance << " " << scene.units << ", " << session.angle_tolerance_deg
      << " deg): "
      << (!session.evaluated  ? "not evaluated (the scene has no assembled pose)"
          : session.assembled ? "ASSEMBLED"
                              : "NOT assembled")
      << "\n      " << final_error_text(session, scene.units) << "\n";
  return out.str();
}

}  // namespace snapfit
