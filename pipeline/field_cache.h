#pragma once
// On-disk cache of descriptor fields (engine/fields/descriptors.h), in the versioned,
// checksummed, atomically written container of io/cache_file.h. The key holds a hash
// of the mesh content, the grid, every descriptor parameter and option that changes
// the values, and a hash of the kernel sources, so any change recomputes.
#include <functional>
#include <optional>
#include <string>

#include "engine/fields/descriptors.h"

namespace snapfit {

// The full key text, and the cache file path for it under cache_root()/fields.
std::string descriptor_cache_key(const Mesh& mesh, const GridSpec& grid, const DescriptorParams& params,
                                 const DescriptorOptions& options);
std::string descriptor_cache_path(const std::string& key);

// The cached fields, or nothing (missing, stale or corrupt: `note` says why for the
// latter two, and the caller recomputes).
std::optional<DescriptorFields> load_cached_descriptors(const std::string& key,
                                                        const std::function<void(const std::string&)>& note);

// Writes the entry; a failure (unwritable folder, full disk) is reported through
// `note`, never thrown: the fields are still good, only not cached.
void save_cached_descriptors(const std::string& key, const DescriptorFields& fields,
                             const std::function<void(const std::string&)>& note);

}  // namespace snapfit
