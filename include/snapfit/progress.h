#pragma once
// Progress bars for long work (fields, spectra, tuning sweeps), as snapfit's tool draws
// them: on a terminal one line redrawn in place, elsewhere a plain line at each 10 % mark
// or every 10 s.
#include <cstdint>
#include <functional>
#include <iostream>
#include <string>

namespace snapfit {

// A callback for work done in named passes that each report (done, total): one
// progress bar per pass, started when its name first appears and finished when it
// reaches its total (or when the next pass starts).
std::function<void(const std::string&, std::uint64_t, std::uint64_t)> pass_progress_bars(std::ostream& out = std::cerr);

}  // namespace snapfit
