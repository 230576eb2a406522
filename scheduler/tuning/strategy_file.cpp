#include "scheduler/tuning/strategy_file.h"

#include <nlohmann/json.hpp>

#include "core/hash.h"
#include "io/cache_file.h"
#include "scheduler/tuning/engine_tuning.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

constexpr const char* kStrategyFileKind = "snapfit strategy";
constexpr std::uint32_t kStrategyFileVersion = 1;

nlohmann::json triple(const double v[3]) { return nlohmann::json::array({v[0], v[1], v[2]}); }

void read_triple(const nlohmann::json& j, double v[3]) {
  for (int i = 0; i < 3; ++i) v[i] = j.at(i).get<double>();
}

}  // namespace

std::string strategy_file_path(const std::string& key) {
  return cache_root() + "/strategy/" + hex64(fnv1a64(key)) + ".strategy";
}

std::string accuracy_report_to_json(const AccuracyReport& r) {
  nlohmann::json strategies = nlohmann::json::array();
  for (const StrategyAccuracy& s : r.strategies)
    strategies.push_back({{"name", s.name},
                          {"interpolation", interpolation_name(s.variant.interpolation)},
                          {"exact_product", s.variant.rotation == RotationMethod::exact_product},
                          {"background", s.variant.product_update == ProductUpdate::background},
                          {"near_far", s.variant.near_far},
                          {"modes", s.modes},
                          {"fits", s.fits},
                          {"frame_ms_p50", s.frame_ms_p50},
                          {"frame_ms_p99", s.frame_ms_p99},
                          {"errors", {s.energy_error, s.force_error, s.torque_error}},
                          {"estimate_coverage", triple(s.estimate_coverage)},
                          {"estimate_ratio_median", triple(s.estimate_ratio_median)},
                          {"product_ms", s.product_ms}});
  const nlohmann::json j = {{"poses", r.poses},
                            {"reference_modes", r.reference_modes},
                            {"reference_seconds", r.reference_seconds},
                            {"strategies", strategies},
                            {"best", r.best}};
  return j.dump(1);
}

AccuracyReport accuracy_report_from_json(const std::string& text, const QueryVariant& base) {
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    AccuracyReport r;
    r.poses = j.at("poses").get<std::size_t>();
    r.reference_modes = j.at("reference_modes").get<std::size_t>();
    r.reference_seconds = j.at("reference_seconds").get<double>();
    for (const auto& e : j.at("strategies")) {
      StrategyAccuracy s;
      s.variant = base;
      s.variant.interpolation =
          interpolation_named(e.at("interpolation").get<std::string>()).value_or(Interpolation::tricubic);
      if (e.at("exact_product").get<bool>()) {
        s.variant.rotation = RotationMethod::exact_product;
        s.variant.product_update =
            e.at("background").get<bool>() ? ProductUpdate::background : ProductUpdate::each_query;
      }
      s.variant.near_far = e.value("near_far", false);
      s.name = variant_name(s.variant);
      if (s.name != e.at("name").get<std::string>()) throw Error("strategy '" + s.name + "' does not match its name");
      s.modes = e.at("modes").get<std::size_t>();
      s.fits = e.at("fits").get<bool>();
      s.frame_ms_p50 = e.at("frame_ms_p50").get<double>();
      s.frame_ms_p99 = e.at("frame_ms_p99").get<double>();
      const auto& errors = e.at("errors");
      s.energy_error = errors.at(0).get<double>();
      s.force_error = errors.at(1).get<double>();
      s.torque_error = errors.at(2).get<double>();
      read_triple(e.at("estimate_coverage"), s.estimate_coverage);
      read_triple(e.at("estimate_ratio_median"), s.estimate_ratio_median);
      s.product_ms = e.at("product_ms").get<double>();
      if (s.modes == 0) throw Error("a strategy without m'");
      r.strategies.push_back(s);
    }
    if (r.strategies.empty()) throw Error("no strategies");
    r.best = lowest_error_that_fits(r.strategies);
    if (r.best != j.at("best").get<std::size_t>()) throw Error("the chosen strategy does not follow the rule");
    r.loop = r.best;
    r.why = strategy_reason(r.strategies, r.best);
    return r;
  } catch (const std::exception& e) {
    throw Error(std::string("strategy file: malformed (") + e.what() + ")");
  }
}

std::optional<AccuracyReport> load_strategy(const std::string& key, const QueryVariant& base,
                                            const std::function<void(const std::string&)>& note) {
  const std::string path = strategy_file_path(key);
  const CacheRead read = read_cache_file(path, kStrategyFileKind, kStrategyFileVersion, key);
  if (read.status != CacheStatus::hit) {
    if (note && read.status != CacheStatus::missing)
      note("strategy file " + path + " not used: " + read.reason + "; measuring again");
    return std::nullopt;
  }
  try {
    return accuracy_report_from_json(std::string(read.payload.begin(), read.payload.end()), base);
  } catch (const Error& e) {
    if (note) note("strategy file " + path + " not used: " + e.what() + "; measuring again");
    return std::nullopt;
  }
}

void save_strategy(const std::string& key, const AccuracyReport& report) {
  const std::string payload = accuracy_report_to_json(report);
  write_cache_file(strategy_file_path(key), kStrategyFileKind, kStrategyFileVersion, key, payload.data(),
                   payload.size());
}

}  // namespace snapfit
