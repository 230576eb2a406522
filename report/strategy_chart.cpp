#include "report/strategy_chart.h"

#include <algorithm>
#include <sstream>

#include "snapfit/accuracy.h"

namespace snapfit {

Chart strategy_chart(const std::vector<StrategyAccuracy>& strategies, double budget_ms) {
  Chart c;
  c.title = "Error against frame time, per query strategy (budget " + std::to_string(budget_ms).substr(0, 4) + " ms)";
  c.x_label = "frame time p99 (ms)";
  c.y_label = "error against the exact reference (%)";
  c.log_y = true;
  Series e{"energy", {}, {}, Series::Style::points, ""}, f{"force", {}, {}, Series::Style::points, ""},
      t{"torque", {}, {}, Series::Style::points, ""};
  for (const StrategyAccuracy& s : strategies) {
    const double x = s.frame_ms_p99;
    e.x.push_back(x), e.y.push_back(100 * s.energy_error);
    f.x.push_back(x), f.y.push_back(100 * s.force_error);
    if (s.variant.torque) t.x.push_back(x), t.y.push_back(100 * s.torque_error);
    std::ostringstream label;
    label << strategy_short_name(s.variant) << ", m' " << s.modes << (s.fits ? "" : " (does not fit)");
    const double rendered = std::max(s.force_error, s.variant.torque ? s.torque_error : 0.0);
    c.markers.push_back(Marker{x, 100 * rendered, label.str()});
  }
  c.series = {e, f};
  if (!t.x.empty()) c.series.push_back(t);
  return c;
}

}  // namespace snapfit
