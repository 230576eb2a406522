#include "engine/maps/map_fft_choice.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <sstream>

#include "core/hash.h"
#include "engine/maps/rotation_search.h"
#include "engine/runtime/kernel_sources.h"
#include "io/cache_file.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

constexpr const char* kKind = "snapfit map fft choice";
constexpr std::uint32_t kVersion = 3;  // 3: batches of rotations timed too
constexpr int kWarmUp = 2, kTimed = 5;

std::string choice_key(const ComputeContext& ctx, const PairSpectra& spectra, Interpolation interpolation) {
  std::ostringstream key;
  key << "platform=" << ctx.device.info.platform_name << "\ndevice=" << ctx.device.info.name
      << "\ndriver=" << ctx.device.info.driver_version << "\ndims=" << spectra.dims[0] << "x" << spectra.dims[1] << "x"
      << spectra.dims[2] << "\ninterpolation=" << interpolation_name(interpolation) << "\nkernels="
      << hex64(fnv1a64(kernel_source("spectrum_sample") + kernel_source("full_map") + kernel_source("map_minima")))
      << "\nbackends=";
  for (MapFft fft : map_ffts_built()) key << map_fft_name(fft) << ",";
  return key.str();
}

// Seconds per map as the search maps them (scan_rotations: two batches in flight, the
// minima found on the device or the host), over fixed rotations: the time from the last
// warm-up map to the last map over the maps between. (Single intervals alternate between
// a wait and a map already done, so a median of them would not be the rate.) A batched
// mapper warms up with a whole batch and is timed over the next.
double seconds_per_map(TranslationMapper& mapper) {
  const int warm_up = std::max(kWarmUp, int(mapper.batch()));
  const int timed = std::max(kTimed, int(mapper.batch()));
  const int n = warm_up + timed;
  std::vector<Eigen::Quaterniond> rotations;
  std::vector<std::size_t> indices;
  for (int i = 0; i < n; ++i) {
    rotations.emplace_back(Eigen::AngleAxisd(0.7 + 0.9 * i, Eigen::Vector3d(1.0, 0.3 * i - 1.0, 0.5).normalized()));
    indices.push_back(std::size_t(i));
  }
  auto start = std::chrono::steady_clock::now();
  int done = 0;
  scan_rotations(mapper, rotations, indices, ScanOptions{4, 2 * mapper.grid().spacing}, [&] {
    if (++done == warm_up) start = std::chrono::steady_clock::now();
  });
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / timed;
}

std::string encode(const MapFftChoice& c) {
  std::ostringstream s;
  s.precision(17);
  s << map_fft_name(c.fft) << " " << c.batch;
  for (const MapFftTiming& t : c.timings) s << " " << map_fft_name(t.fft) << " " << t.batch << " " << t.seconds;
  return s.str();
}

bool decode(const std::string& text, MapFftChoice& c, std::size_t candidates) {
  std::istringstream s(text);
  std::string name;
  if (!(s >> name >> c.batch) || c.batch == 0) return false;
  try {
    c.fft = parse_map_fft(name);
    std::size_t batch = 0;
    for (double seconds; s >> name >> batch >> seconds;) c.timings.push_back({parse_map_fft(name), batch, seconds});
  } catch (const Error&) {
    return false;
  }
  return c.timings.size() == candidates;
}

// Each backend one rotation at a time, then the device FFTs in batches of `batch` (> 1).
std::vector<MapFftTiming> candidates(std::size_t batch) {
  std::vector<MapFftTiming> list;
  for (MapFft fft : map_ffts_built()) list.push_back({fft, 1, 0.0});
  if (batch > 1)
    for (MapFft fft : map_ffts_built())
      if (map_fft_on_device(fft)) list.push_back({fft, batch, 0.0});
  return list;
}

}  // namespace

MapFftChoice choose_map_fft(const FftLibrary& library, const ComputeContext& ctx, const PairSpectra& spectra,
                            Interpolation interpolation, std::size_t modes, const ProgramCacheConfig& cache) {
  const std::string key = choice_key(ctx, spectra, interpolation);
  const std::string path = cache_root() + "/map_fft/" + hex64(fnv1a64(key)) + ".choice";
  const std::vector<MapFftTiming> tried = candidates(map_batch_limit(ctx, spectra.dims, kMapBatch));
  MapFftChoice choice;
  if (auto payload = read_cache_payload(path, kKind, kVersion, key, "map FFT choice", cache.note)) {
    if (decode(std::string(payload->begin(), payload->end()), choice, tried.size())) {
      choice.cached = true;
      return choice;
    }
    choice = MapFftChoice{};
  }
  for (MapFftTiming t : tried) {
    TranslationMapper mapper(library, ctx, spectra, interpolation, modes, t.fft, cache, t.batch);
    t.seconds = seconds_per_map(mapper);
    choice.timings.push_back(t);
  }
  const MapFftTiming& best = *std::min_element(choice.timings.begin(), choice.timings.end(),
                                               [](const auto& a, const auto& b) { return a.seconds < b.seconds; });
  choice.fft = best.fft;
  choice.batch = best.batch;
  const std::string text = encode(choice);
  try {
    write_cache_file(path, kKind, kVersion, key, text.data(), text.size());
  } catch (const Error& e) {
    if (cache.note) cache.note(std::string("map FFT choice not cached: ") + e.what());
  }
  return choice;
}

std::string describe_map_fft_choice(const MapFftChoice& choice) {
  auto name = [](MapFft fft, std::size_t batch) {
    return map_fft_name(fft) + (batch > 1 ? " x" + std::to_string(batch) : std::string());
  };
  std::string text = name(choice.fft, choice.batch) + " (per map:";
  char ms[32];
  for (std::size_t i = 0; i < choice.timings.size(); ++i) {
    std::snprintf(ms, sizeof ms, " %.1f ms", 1e3 * choice.timings[i].seconds);
    text += (i ? "," : "") + std::string(" ") + name(choice.timings[i].fft, choice.timings[i].batch) + ms;
  }
  return text + (choice.cached ? "; cached)" : "; measured)");
}

}  // namespace snapfit
