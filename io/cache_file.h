#pragma once
// Versioned, checksummed cache files written atomically (temp file + rename), for
// every on-disk cache of snapfit (program binaries, fields, spectra, tuning).
//
// Layout (little-endian):  "SNAPFIT\0" | u32 container version | u32 len + kind |
// u32 payload version | u32 len + key text | u64 payload size | u64 FNV-1a(payload) | payload
// The full key text is stored, so a file-name hash collision can never return the
// wrong entry; a reader that finds any mismatch treats the entry as absent.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace snapfit {

// Root of snapfit's caches: $SNAPFIT_CACHE_DIR, else $XDG_CACHE_HOME/snapfit, else
// $HOME/.cache/snapfit, else <temp>/snapfit-cache. Not created here.
std::string cache_root();

enum class CacheStatus {
  hit,      // payload returned
  missing,  // no file
  stale,    // readable, but written for another kind, version or key
  corrupt,  // truncated, bad magic, or checksum mismatch
};

struct CacheRead {
  CacheStatus status = CacheStatus::missing;
  std::string reason;                  // why it is not a hit, for messages
  std::vector<unsigned char> payload;  // only on a hit
};

CacheRead read_cache_file(const std::string& path, const std::string& kind, std::uint32_t version,
                          const std::string& key);

// The payload of a hit; nothing for a missing entry, and for a stale or corrupt one
// nothing with a note: "<what> <path> is corrupt (<reason>); recomputing".
std::optional<std::vector<unsigned char>> read_cache_payload(const std::string& path, const std::string& kind,
                                                             std::uint32_t version, const std::string& key,
                                                             const std::string& what,
                                                             const std::function<void(const std::string&)>& note);

// Creates parent folders and writes through io/atomic_write.h, so a
// reader sees the old file or the new one, never half of one. Throws snapfit::Error
// naming the path on failure (unwritable folder, full disk); no temp file is left.
void write_cache_file(const std::string& path, const std::string& kind, std::uint32_t version, const std::string& key,
                      const void* payload, std::size_t payload_size);

}  // namespace snapfit
