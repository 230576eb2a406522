#include "pipeline/spectra_cache.h"

#include <cstring>
#include <filesystem>
#include <sstream>

#include "core/hash.h"
#include "io/cache_file.h"
#include "io/cache_payload.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

// 2: each part's sample parity (engine/spectra/spectra.h). 3: part 2's deconvolved spectrum and
// its kernel width in place of the torque moments.
constexpr std::uint32_t kSpectraCacheVersion = 4;  // 4: every FFT axis even
constexpr const char* kKind = "pair-spectra";

std::uint64_t field_hash(const DescriptorFields& f) {
  const std::vector<float> rho = affinity_imaginary(f);
  std::ostringstream grid;
  grid.precision(17);
  grid << f.grid.origin.transpose() << " " << f.grid.spacing << " " << f.grid.dims.transpose();
  return fnv1a64(rho.data(), rho.size() * sizeof(float), fnv1a64(grid.str()));
}

// Payload (io/cache_payload.h): a fixed header of doubles and sizes, then the complex
// arrays in order.

std::string path_for(const std::string& key) {
  return (std::filesystem::path(cache_root()) / "spectra" / (hex64(fnv1a64(key)) + ".bin")).string();
}

}  // namespace

std::string spectra_cache_key(const DescriptorFields& part1, const DescriptorFields& part2,
                              const SpectrumOptions& options, const std::string& source1, const std::string& source2) {
  std::ostringstream key;
  key.precision(17);
  key << "fields1=" << hex64(field_hash(part1)) << "|fields2=" << hex64(field_hash(part2))
      << "|oversampling=" << options.oversampling << "|exact_rotation_width=" << options.exact_rotation_width
      << "|source1=" << source1 << "|source2=" << source2;
  return key.str();
}

std::optional<PairSpectra> load_cached_spectra(const std::string& key,
                                               const std::function<void(const std::string&)>& note) {
  const std::string path = path_for(key);
  const std::optional<std::vector<unsigned char>> payload =
      read_cache_payload(path, kKind, kSpectraCacheVersion, key, "spectra cache", note);
  if (!payload) return std::nullopt;
  PayloadReader r{*payload};
  PairSpectra s;
  for (auto& d : s.dims) d = r.get<std::uint64_t>();
  s.spacing = r.get<double>();
  s.length = r.get_vector3<Eigen::Vector3d>();
  for (PartSpectrum* part : {&s.part1, &s.part2}) {
    part->centre = r.get_vector3<Eigen::Vector3d>();
    part->half_extent = r.get_vector3<Eigen::Vector3d>();
    part->sample_parity = r.get<std::int8_t>();
    part->rho = r.get_array<Complex>();
    part->deconvolved = r.get_array<Complex>();
    part->deconvolved_width = r.get<std::int32_t>();
  }
  const std::size_t count = s.dims[0] * s.dims[1] * s.dims[2];
  if (!r.ok || r.at != payload->size() || s.part1.rho.size() != count || s.part2.rho.size() != count) {
    note("spectra cache " + path + " does not hold what its header says; recomputing");
    return std::nullopt;
  }
  return s;
}

void save_cached_spectra(const std::string& key, const PairSpectra& s,
                         const std::function<void(const std::string&)>& note) {
  PayloadWriter w;
  for (auto d : s.dims) w.put<std::uint64_t>(d);
  w.put(s.spacing);
  w.put_vector3(s.length);
  for (const PartSpectrum* part : {&s.part1, &s.part2}) {
    w.put_vector3(part->centre);
    w.put_vector3(part->half_extent);
    w.put<std::int8_t>(static_cast<std::int8_t>(part->sample_parity));
    w.put_array(part->rho);
    w.put_array(part->deconvolved);
    w.put<std::int32_t>(part->deconvolved_width);
  }
  try {
    write_cache_file(path_for(key), kKind, kSpectraCacheVersion, key, w.bytes.data(), w.bytes.size());
  } catch (const Error& e) {
    note(std::string("spectra not cached: ") + e.what());
  }
}

}  // namespace snapfit
