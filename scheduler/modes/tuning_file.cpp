#include "scheduler/modes/tuning_file.h"

#include <nlohmann/json.hpp>
#include <sstream>

#include "core/hash.h"
#include "io/cache_file.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

constexpr const char* kTuningFileKind = "snapfit tuning";
constexpr std::uint32_t kTuningFileVersion = 1;

}  // namespace

std::string TuningKey::text() const {
  std::ostringstream s;
  s.precision(17);
  s << "platform=" << platform << "\ndevice=" << device << "\ndriver=" << driver << "\nvariant=" << variant
    << "\nscene=" << scene_features << "\nbudget_ms=" << budget_ms << "\nmargin=" << margin << "\npace_hz=" << pace_hz;
  return s.str();
}

std::string tuning_file_path(const TuningKey& key) {
  return cache_root() + "/tuning/" + hex64(fnv1a64(key.text())) + ".tuning";
}

std::string tuning_to_json(const TuningResult& r) {
  nlohmann::json points = nlohmann::json::array();
  for (const TimingPoint& p : r.points)
    points.push_back(
        {{"modes", p.modes}, {"p50_ms", p.p50_ms}, {"p99_ms", p.p99_ms}, {"max_ms", p.max_ms}, {"samples", p.samples}});
  const nlohmann::json j = {{"points", points},
                            {"model", {{"fixed_ms", r.model.fixed_ms}, {"per_mode_ms", r.model.per_mode_ms}}},
                            {"chosen_modes", r.chosen_modes},
                            {"fits", r.fits},
                            {"budget_ms", r.budget_ms},
                            {"margin", r.margin},
                            {"created", r.created}};
  return j.dump(1);
}

TuningResult tuning_from_json(const std::string& text) {
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    TuningResult r;
    for (const auto& p : j.at("points"))
      r.points.push_back(TimingPoint{p.at("modes").get<std::size_t>(), p.at("p50_ms").get<double>(),
                                     p.at("p99_ms").get<double>(), p.at("max_ms").get<double>(),
                                     p.at("samples").get<std::size_t>()});
    r.model.fixed_ms = j.at("model").at("fixed_ms").get<double>();
    r.model.per_mode_ms = j.at("model").at("per_mode_ms").get<double>();
    r.chosen_modes = j.at("chosen_modes").get<std::size_t>();
    r.fits = j.at("fits").get<bool>();
    r.budget_ms = j.at("budget_ms").get<double>();
    r.margin = j.at("margin").get<double>();
    r.created = j.at("created").get<std::string>();
    if (r.points.empty() || r.chosen_modes == 0) throw Error("no timings");
    return r;
  } catch (const std::exception& e) {
    throw Error(std::string("tuning result: malformed (") + e.what() + ")");
  }
}

std::optional<TuningResult> load_tuning(const TuningKey& key, const std::function<void(const std::string&)>& note) {
  const std::string path = tuning_file_path(key);
  const CacheRead read = read_cache_file(path, kTuningFileKind, kTuningFileVersion, key.text());
  if (read.status != CacheStatus::hit) {
    if (note && read.status != CacheStatus::missing)
      note("tuning file " + path + " not used: " + read.reason + "; re-tuning");
    return std::nullopt;
  }
  try {
    return tuning_from_json(std::string(read.payload.begin(), read.payload.end()));
  } catch (const Error& e) {
    if (note) note("tuning file " + path + " not used: " + e.what() + "; re-tuning");
    return std::nullopt;
  }
}

void save_tuning(const TuningKey& key, const TuningResult& result) {
  const std::string payload = tuning_to_json(result);
  write_cache_file(tuning_file_path(key), kTuningFileKind, kTuningFileVersion, key.text(), payload.data(), payload.size());
}

}  // namespace snapfit
