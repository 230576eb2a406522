#include "pipeline/field_cache.h"

#include <cstring>
#include <filesystem>
#include <sstream>

#include "core/hash.h"
#include "engine/runtime/kernel_sources.h"
#include "io/cache_file.h"
#include "mesh/mesh_hash.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

// 3: fields computed in grid units (engine/fields/descriptors.cpp).
constexpr std::uint32_t kFieldCacheVersion = 3;
// Mask bit (above the field bits) set when w came from sign propagation.
constexpr std::uint32_t kSignPropagationBit = 1u << 16;
constexpr const char* kKind = "descriptor-fields";

// Payload: u64 point count, u32 mask of present fields (plus kSignPropagationBit), then
// each present field's floats, in this order.
template <typename Fields>
auto field_list(Fields& f) {
  return std::vector<decltype(&f.winding)>{&f.winding, &f.winding_bound, &f.signed_distance, &f.skeletal_density,
                                           &f.density_bound};
}

}  // namespace

std::string descriptor_cache_key(const Mesh& mesh, const GridSpec& grid, const DescriptorParams& params,
                                 const DescriptorOptions& options) {
  std::ostringstream key;
  key.precision(17);
  std::uint64_t sources = 0;
  for (const char* name : {"geometry", "unsigned_distance", "winding_number", "skeletal_density"})
    sources = fnv1a64(kernel_source(name)) ^ (sources * 1099511628211ull);
  key << "mesh=" << hex64(mesh_hash(mesh)) << "|grid=" << grid.origin.x() << "," << grid.origin.y() << ","
      << grid.origin.z() << "," << grid.spacing << "," << grid.dims.x() << "," << grid.dims.y() << "," << grid.dims.z()
      << "|kind=" << (params.kind == DescriptorKind::skeletal_density ? "skeletal" : "indicator");
  if (params.kind == DescriptorKind::skeletal_density)
    key << "|sigma=" << params.sigma << "|refine=" << options.refine_fraction
        << "|brute_force=" << options.brute_force_density;
  key << "|leaf=" << options.bvh_leaf_size
      << "|xi=" << (params.kind == DescriptorKind::skeletal_density || options.indicator_signed_distance)
      << "|tolerance=" << params.tolerance << "|min_distance=" << options.min_distance_fraction
      << "|kernels=" << hex64(sources) << "|winding_propagation=" << options.winding_sign_propagation;
  return key.str();
}

std::string descriptor_cache_path(const std::string& key) {
  return (std::filesystem::path(cache_root()) / "fields" / (hex64(fnv1a64(key)) + ".bin")).string();
}

std::optional<DescriptorFields> load_cached_descriptors(const std::string& key,
                                                        const std::function<void(const std::string&)>& note) {
  const std::string path = descriptor_cache_path(key);
  const std::optional<std::vector<unsigned char>> payload =
      read_cache_payload(path, kKind, kFieldCacheVersion, key, "field cache", note);
  if (!payload) return std::nullopt;
  DescriptorFields fields;
  const std::vector<unsigned char>& bytes = *payload;
  std::uint64_t count = 0;
  std::uint32_t mask = 0;
  if (bytes.size() < 12) {
    note("field cache " + path + " has a short payload; recomputing");
    return std::nullopt;
  }
  std::memcpy(&count, bytes.data(), 8);
  std::memcpy(&mask, bytes.data() + 8, 4);
  std::size_t at = 12;
  if (mask & kSignPropagationBit) fields.winding_method = "sign propagation";
  for (std::size_t i = 0; i < field_list(fields).size(); ++i) {
    if (!(mask & (1u << i))) continue;
    if (bytes.size() - at < count * sizeof(float)) {
      note("field cache " + path + " is shorter than its header says; recomputing");
      return std::nullopt;
    }
    std::vector<float>& v = *field_list(fields)[i];
    v.resize(count);
    std::memcpy(v.data(), bytes.data() + at, count * sizeof(float));
    at += count * sizeof(float);
  }
  return fields;  // grid and params are the caller's (they are in the key)
}

void save_cached_descriptors(const std::string& key, const DescriptorFields& fields,
                             const std::function<void(const std::string&)>& note) {
  const auto list = field_list(fields);
  const std::uint64_t count = fields.winding.size();
  std::uint32_t mask = 0;
  std::vector<unsigned char> payload(12);
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (list[i]->empty()) continue;
    mask |= 1u << i;
    const auto* raw = reinterpret_cast<const unsigned char*>(list[i]->data());
    payload.insert(payload.end(), raw, raw + list[i]->size() * sizeof(float));
  }
  if (fields.winding_method == "sign propagation") mask |= kSignPropagationBit;
  std::memcpy(payload.data(), &count, 8);
  std::memcpy(payload.data() + 8, &mask, 4);
  try {
    write_cache_file(descriptor_cache_path(key), kKind, kFieldCacheVersion, key, payload.data(), payload.size());
  } catch (const Error& e) {
    note(std::string("fields not cached: ") + e.what());
  }
}

}  // namespace snapfit
