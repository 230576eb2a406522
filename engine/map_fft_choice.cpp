#include "engine/map_fft_choice.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <sstream>

#include "core/hash.h"
#include "engine/kernel_sources.h"
#include "engine/rotation_search.h"
#include "io/cache_file.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

constexpr const char* kKind = "snapfit map fft choice";
constexpr std::uint32_t kVersion = 2;  // 2: timed with the minima, found on the device for clFFT
constexpr int kWarmUp = 2, kTimed = 5;

std::string choice_key(const ComputeContext& ctx, const PairSpectra& spectra, Interpolation interpolation) {
  std::ostringstream key;
  key << "platform=" << ctx.device.info.platform_name << "\ndevice=" << ctx.device.info.name
      << "\ndriver=" << ctx.device.info.driver_version << "\ndims=" << spectra.dims[0] << "x" << spectra.dims[1] << "x"
      << spectra.dims[2] << "\ninterpolation=" << (interpolation == Interpolation::tricubic ? "tricubic" : "trilinear")
      << "\nkernels="
      << hex64(fnv1a64(kernel_source("spectrum_sample") + kernel_source("full_map") + kernel_source("map_minima")))
      << "\nbackends=";
  for (MapFft fft : map_ffts_built()) key << map_fft_name(fft) << ",";
  return key.str();
}

// Seconds per map as the search maps them (scan_rotations: two in flight, the minima
// found on the device or the host), over fixed rotations: the time from the last
// warm-up map to the last map over the maps between. (Single intervals alternate between
// a wait and a map already done, so a median of them would not be the rate.)
double seconds_per_map(TranslationMapper& mapper) {
  const int n = kWarmUp + kTimed;
  std::vector<Eigen::Quaterniond> rotations;
  std::vector<std::size_t> indices;
  for (int i = 0; i < n; ++i) {
    rotations.emplace_back(Eigen::AngleAxisd(0.7 + 0.9 * i, Eigen::Vector3d(1.0, 0.3 * i - 1.0, 0.5).normalized()));
    indices.push_back(std::size_t(i));
  }
  auto start = std::chrono::steady_clock::now();
  int done = 0;
  scan_rotations(mapper, rotations, indices, ScanOptions{4, 2 * mapper.grid().spacing}, [&] {
    if (++done == kWarmUp) start = std::chrono::steady_clock::now();
  });
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / kTimed;
}

std::string encode(const MapFftChoice& c) {
  std::ostringstream s;
  s.precision(17);
  s << map_fft_name(c.fft);
  for (const MapFftTiming& t : c.timings) s << " " << map_fft_name(t.fft) << " " << t.seconds;
  return s.str();
}

bool decode(const std::string& text, MapFftChoice& c) {
  std::istringstream s(text);
  std::string name;
  if (!(s >> name)) return false;
  try {
    c.fft = parse_map_fft(name);
    for (double seconds; s >> name >> seconds;) c.timings.push_back({parse_map_fft(name), seconds});
  } catch (const Error&) {
    return false;
  }
  return c.timings.size() == map_ffts_built().size();
}

}  // namespace

MapFftChoice choose_map_fft(const FftLibrary& library, const ComputeContext& ctx, const PairSpectra& spectra,
                            Interpolation interpolation, std::size_t modes, const ProgramCacheConfig& cache) {
  const std::string key = choice_key(ctx, spectra, interpolation);
  const std::string path = cache_root() + "/map_fft/" + hex64(fnv1a64(key)) + ".choice";
  MapFftChoice choice;
  if (auto payload = read_cache_payload(path, kKind, kVersion, key, "map FFT choice", cache.note)) {
    if (decode(std::string(payload->begin(), payload->end()), choice)) {
      choice.cached = true;
      return choice;
    }
    choice = MapFftChoice{};
  }
  for (MapFft fft : map_ffts_built()) {
    TranslationMapper mapper(library, ctx, spectra, interpolation, modes, fft, cache);
    choice.timings.push_back({fft, seconds_per_map(mapper)});
  }
  choice.fft = std::min_element(choice.timings.begin(), choice.timings.end(), [](const auto& a, const auto& b) {
                 return a.seconds < b.seconds;
               })->fft;
  const std::string text = encode(choice);
  try {
    write_cache_file(path, kKind, kVersion, key, text.data(), text.size());
  } catch (const Error& e) {
    if (cache.note) cache.note(std::string("map FFT choice not cached: ") + e.what());
  }
  return choice;
}

std::string describe_map_fft_choice(const MapFftChoice& choice) {
  std::string text = map_fft_name(choice.fft) + " (per map:";
  char ms[32];
  for (std::size_t i = 0; i < choice.timings.size(); ++i) {
    std::snprintf(ms, sizeof ms, " %.1f ms", 1e3 * choice.timings[i].seconds);
    text += (i ? "," : "") + std::string(" ") + map_fft_name(choice.timings[i].fft) + ms;
  }
  return text + (choice.cached ? "; cached)" : "; measured)");
}

}  // namespace snapfit
