#pragma once
// The query strategies of an accuracy report side by side: each one's error of E, F and T
// against the exact reference (log scale) at its frame time (the p99 it was timed at), a
// labelled ring on each strategy's rendered error (the larger of F and T). report.html
// draws it under the strategy the loop rendered; `snapfit accuracy --html` writes it as a
// page.
#include <string>
#include <vector>

#include "report/chart_spec.h"
#include "snapfit/accuracy.h"

namespace snapfit {


Chart strategy_chart(const std::vector<StrategyAccuracy>& strategies, double budget_ms);

}  // namespace snapfit
