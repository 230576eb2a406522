#pragma once
// The strategy file: what `snapfit accuracy` measured for a scene on a device (each
// query strategy's tuned m', frame time and error against the exact reference, and the
// one chosen), kept in the cache folder (<cache root>/strategy/, io/cache_file.h:
// versioned, checksummed, written atomically) so that `snapfit run` renders the most
// accurate strategy that fits without measuring the reference again. Keyed by the
// tuning keys of every candidate (device, driver, kernels, scene features, budget,
// margin, pace) and the number of reference poses; a file for another key, a corrupt
// file or a missing one reads as absent (with the reason).
#include <functional>
#include <optional>
#include <string>

#include "scheduler/tuning/accuracy.h"

namespace snapfit {

std::string strategy_file_path(const std::string& key);

// The report as JSON text, and back; `base` is the scene's loop variant, from which each
// strategy's variant is rebuilt (throws snapfit::Error on malformed text).
std::string accuracy_report_to_json(const AccuracyReport& report);
AccuracyReport accuracy_report_from_json(const std::string& text, const QueryVariant& base);

std::optional<AccuracyReport> load_strategy(const std::string& key, const QueryVariant& base,
                                            const std::function<void(const std::string&)>& note = nullptr);

// Throws snapfit::Error naming the path when the cache folder cannot be written.
void save_strategy(const std::string& key, const AccuracyReport& report);

}  // namespace snapfit
