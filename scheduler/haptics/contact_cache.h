#pragma once
// On-disk cache of the rigid contact's geometry (scheduler/haptics/rigid_contact.h): both parts'
// distance grids and surface samples, which take seconds to build, in io/cache_file.h's
// versioned, checksummed, atomically written container under cache_root()/contact. The
// key holds both meshes' content hashes and every spacing the geometry depends on; the
// stiffness, skin and units are set by the caller and are not cached.
#include <optional>
#include <string>

#include "scheduler/haptics/rigid_contact.h"

namespace snapfit {

std::string contact_cache_key(const Mesh& part1, const Mesh& part2, double sample_spacing, double distance_spacing,
                              double band, const Eigen::AlignedBox3d* part1_region = nullptr);
std::string contact_cache_path(const std::string& key);

// The cached geometry, or nothing (missing, stale, corrupt or malformed: recompute).
std::optional<RigidContactModel> load_cached_contact(const std::string& key);

// Writes the entry; returns false when it cannot (unwritable folder, full disk): the
// model is still good, only not cached.
bool save_cached_contact(const std::string& key, const RigidContactModel& model);

}  // namespace snapfit
