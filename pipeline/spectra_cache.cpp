#include "pipeline/spectra_cache.h"

#include <cstring>
#include <filesystem>
#include <sstream>

#include "core/hash.h"
#include "io/cache_file.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

// 2: each part's sample parity (engine/spectra.h). 3: part 2's deconvolved spectrum and
// its kernel width in place of the torque moments.
constexpr std::uint32_t kSpectraCacheVersion = 3;
constexpr const char* kKind = "pair-spectra";

std::uint64_t field_hash(const DescriptorFields& f) {
  const std::vector<float> rho = affinity_imaginary(f);
  std::ostringstream grid;
  grid.precision(17);
  grid << f.grid.origin.transpose() << " " << f.grid.spacing << " " << f.grid.dims.transpose();
  return fnv1a64(rho.data(), rho.size() * sizeof(float), fnv1a64(grid.str()));
}

// Payload: a fixed header of doubles and sizes, then the complex arrays in order.
struct Writer {
  std::vector<unsigned char> bytes;
  template <typename T>
  void put(const T& value) {
    const auto* p = reinterpret_cast<const unsigned char*>(&value);
    bytes.insert(bytes.end(), p, p + sizeof(T));
  }
  void put_array(const std::vector<Complex>& v) {
    put<std::uint64_t>(v.size());
    const auto* p = reinterpret_cast<const unsigned char*>(v.data());
    bytes.insert(bytes.end(), p, p + v.size() * sizeof(Complex));
  }
};

struct Reader {
  const std::vector<unsigned char>& bytes;
  std::size_t at = 0;
  bool ok = true;
  template <typename T>
  T get() {
    T value{};
    if (!ok || bytes.size() - at < sizeof(T)) return ok = false, value;
    std::memcpy(&value, bytes.data() + at, sizeof(T));
    at += sizeof(T);
    return value;
  }
  std::vector<Complex> get_array() {
    const std::uint64_t n = get<std::uint64_t>();
    if (!ok || (bytes.size() - at) / sizeof(Complex) < n) return ok = false, std::vector<Complex>();
    std::vector<Complex> v(n);
    std::memcpy(v.data(), bytes.data() + at, n * sizeof(Complex));
    at += n * sizeof(Complex);
    return v;
  }
};

void put_vector(Writer& w, const Eigen::Vector3d& v) {
  for (int a = 0; a < 3; ++a) w.put(v[a]);
}
Eigen::Vector3d get_vector(Reader& r) {
  Eigen::Vector3d v;
  for (int a = 0; a < 3; ++a) v[a] = r.get<double>();
  return v;
}

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
  Reader r{*payload};
  PairSpectra s;
  for (auto& d : s.dims) d = r.get<std::uint64_t>();
  s.spacing = r.get<double>();
  s.length = get_vector(r);
  for (PartSpectrum* part : {&s.part1, &s.part2}) {
    part->centre = get_vector(r);
    part->half_extent = get_vector(r);
    part->sample_parity = r.get<std::int8_t>();
    part->rho = r.get_array();
    part->deconvolved = r.get_array();
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
  Writer w;
  for (auto d : s.dims) w.put<std::uint64_t>(d);
  w.put(s.spacing);
  put_vector(w, s.length);
  for (const PartSpectrum* part : {&s.part1, &s.part2}) {
    put_vector(w, part->centre);
    put_vector(w, part->half_extent);
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
