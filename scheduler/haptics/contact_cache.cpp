#include "scheduler/haptics/contact_cache.h"

#include <filesystem>
#include <sstream>
#include <vector>

#include "core/hash.h"
#include "io/cache_file.h"
#include "io/cache_payload.h"
#include "mesh/mesh_hash.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

constexpr std::uint32_t kContactCacheVersion = 3;
constexpr const char* kContactCacheKind = "rigid-contact";

void put_grid(PayloadWriter& w, const SignedDistanceGrid& g) {
  w.put_vector3(g.origin), w.put(g.coarse), w.put(std::int32_t(g.refine)), w.put_vector3(g.dims);
  w.put_vector3(g.part_min), w.put_vector3(g.part_max), w.put(g.band);
  w.put_array(g.coarse_values), w.put_array(g.brick_of_cell), w.put_array(g.brick_values), w.put(g.brick_step);
}

// False when what was read cannot be a grid the sampler can use.
bool get_grid(PayloadReader& r, SignedDistanceGrid& g) {
  g.origin = r.get_vector3<Eigen::Vector3d>();
  g.coarse = r.get<double>();
  g.refine = r.get<std::int32_t>();
  g.dims = r.get_vector3<Eigen::Vector3i>();
  g.part_min = r.get_vector3<Eigen::Vector3d>();
  g.part_max = r.get_vector3<Eigen::Vector3d>();
  g.band = r.get<double>();
  g.coarse_values = r.get_array<float>();
  g.brick_of_cell = r.get_array<std::int32_t, decltype(g.brick_of_cell)::allocator_type>();
  g.brick_values = r.get_array<std::int16_t, decltype(g.brick_values)::allocator_type>();
  g.brick_step = r.get<double>();
  if (!r.ok || !(g.brick_step > 0) || g.refine < 1 || g.refine > 16 || !(g.coarse > 0) || (g.dims.array() < 2).any()) return false;
  const std::size_t nodes = std::size_t(g.dims.x()) * g.dims.y() * g.dims.z();
  const std::size_t cells = std::size_t(g.dims.x() - 1) * (g.dims.y() - 1) * (g.dims.z() - 1);
  if (g.coarse_values.size() != nodes || g.brick_of_cell.size() != cells || g.brick_values.size() % g.brick_nodes())
    return false;
  for (std::int32_t b : g.brick_of_cell)
    if (b >= std::int32_t(g.bricks()) || b < kCoarseInside) return false;
  return true;
}

// Chunks as (centre, radius, begin, end) in plain types.
struct ChunkRecord {
  double centre[3];
  double radius;
  std::uint64_t begin, end;
};

void put_samples(PayloadWriter& w, const ContactSamples& s) {
  std::vector<double> xyz;
  xyz.reserve(3 * s.points.size());
  for (const Eigen::Vector3d& p : s.points) xyz.insert(xyz.end(), {p.x(), p.y(), p.z()});
  std::vector<ChunkRecord> chunks;
  for (const ShellChunk& c : s.chunks)
    chunks.push_back({{c.centre.x(), c.centre.y(), c.centre.z()}, c.radius, c.begin, c.end});
  w.put_array(xyz), w.put_array(s.areas), w.put_array(chunks);
  w.put(std::uint64_t(s.face_points)), w.put(std::uint64_t(s.feature_points)), w.put(s.spacing);
}

bool get_samples(PayloadReader& r, ContactSamples& s) {
  const std::vector<double> xyz = r.get_array<double>();
  s.areas = r.get_array<double>();
  const std::vector<ChunkRecord> chunks = r.get_array<ChunkRecord>();
  s.face_points = r.get<std::uint64_t>();
  s.feature_points = r.get<std::uint64_t>();
  s.spacing = r.get<double>();
  if (!r.ok || xyz.size() % 3 || s.areas.size() != xyz.size() / 3) return false;
  for (std::size_t i = 0; i < xyz.size(); i += 3) s.points.emplace_back(xyz[i], xyz[i + 1], xyz[i + 2]);
  for (const ChunkRecord& c : chunks) {
    if (c.begin > c.end || c.end > s.points.size()) return false;
    s.chunks.push_back(ShellChunk{Eigen::Vector3d(c.centre[0], c.centre[1], c.centre[2]), c.radius,
                                  std::size_t(c.begin), std::size_t(c.end)});
  }
  return true;
}

}  // namespace

std::string contact_cache_key(const Mesh& part1, const Mesh& part2, double sample_spacing, double distance_spacing,
                              double band, const Eigen::AlignedBox3d* part1_region) {
  std::ostringstream key;
  key.precision(17);
  key << "part1=" << hex64(mesh_hash(part1)) << "|part2=" << hex64(mesh_hash(part2)) << "|samples=" << sample_spacing
      << "|distance=" << distance_spacing << "|band=" << band;
  if (part1_region)
    key << "|region=" << part1_region->min().transpose() << " " << part1_region->max().transpose();
  return key.str();
}

std::string contact_cache_path(const std::string& key) {
  return (std::filesystem::path(cache_root()) / "contact" / (hex64(fnv1a64(key)) + ".bin")).string();
}

std::optional<RigidContactModel> load_cached_contact(const std::string& key) {
  const CacheRead read = read_cache_file(contact_cache_path(key), kContactCacheKind, kContactCacheVersion, key);
  if (read.status != CacheStatus::hit) return std::nullopt;
  PayloadReader r{read.payload};
  RigidContactModel m;
  const bool ok = get_grid(r, m.part1_distance) && get_grid(r, m.part2_distance) &&
                  get_samples(r, m.part1_samples) && get_samples(r, m.part2_samples);
  if (!ok || !r.finished()) return std::nullopt;
  try {
    prepare_rigid_contact(m);  // the model as build_rigid_contact returns it
  } catch (const Error&) {
    return std::nullopt;  // samples that cannot be blocked (a spacing <= 0): malformed
  }
  return m;
}

bool save_cached_contact(const std::string& key, const RigidContactModel& m) {
  PayloadWriter w;
  put_grid(w, m.part1_distance), put_grid(w, m.part2_distance);
  put_samples(w, m.part1_samples), put_samples(w, m.part2_samples);
  try {
    write_cache_file(contact_cache_path(key), kContactCacheKind, kContactCacheVersion, key, w.bytes.data(), w.bytes.size());
    return true;
  } catch (const Error&) {
    return false;
  }
}

}  // namespace snapfit
