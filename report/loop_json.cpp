#include "report/loop_json.h"

#include "snapfit/quantile.h"

namespace snapfit {
namespace {

nlohmann::json spread_ms(const std::vector<double>& ms) {
  return {{"p50", quantile(ms, 0.5)}, {"p99", quantile(ms, 0.99)}, {"max", quantile(ms, 1.0)}};
}

}  // namespace

nlohmann::json loop_json(const LoopReport& loop) {
  return {{"rate_hz", loop.rate_hz},
          {"measured_rate_hz", loop.measured_rate_hz},
          {"elapsed_s", loop.elapsed_s},
          {"frames", loop.frames},
          {"ticks", loop.ticks},
          {"misses", loop.misses},
          {"skipped_ticks", loop.skipped_ticks},
          {"late_wakeup_misses", loop.late_wakeup_misses},
          {"stall_misses", loop.stall_misses},
          {"wake_late_ms", spread_ms(loop.wake_late_ms)},
          {"miss_rate", loop.miss_rate()},
          {"flagged_frames", loop.flagged_frames},
          {"trust", {{"scaled_frames", loop.trust_scaled_frames}, {"withheld_frames", loop.trust_withheld_frames},
                     {"out_of_region_frames", loop.out_of_region_frames}}},
          {"frame_ms", spread_ms(loop.frame_ms)}};
}

nlohmann::json mode_changes_json(const std::vector<ModeChange>& changes) {
  nlohmann::json out = nlohmann::json::array();
  for (const ModeChange& c : changes)
    out.push_back({{"time_s", c.time_s}, {"frame", c.frame}, {"from", c.from}, {"to", c.to}, {"reason", c.reason}});
  return out;
}

}  // namespace snapfit
