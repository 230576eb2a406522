#include "io/cache_file.h"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/hash.h"
#include "io/atomic_write.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

constexpr char kMagic[8] = {'S', 'N', 'A', 'P', 'F', 'I', 'T', '\0'};
constexpr std::uint32_t kContainerVersion = 1;

void put_u32(std::string& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}
void put_u64(std::string& out, std::uint64_t v) {
  for (int i = 0; i < 8; ++i) out.push_back(static_cast<char>((v >> (8 * i)) & 0xff));
}
void put_text(std::string& out, const std::string& s) {
  put_u32(out, static_cast<std::uint32_t>(s.size()));
  out += s;
}

// A bounds-checked little-endian reader over a byte buffer.
struct Reader {
  const std::vector<unsigned char>& bytes;
  std::size_t at = 0;
  bool ok = true;
  std::uint64_t uint(int size) {
    if (!ok || bytes.size() - at < static_cast<std::size_t>(size)) return ok = false, 0;
    std::uint64_t v = 0;
    for (int i = 0; i < size; ++i) v |= static_cast<std::uint64_t>(bytes[at + i]) << (8 * i);
    at += size;
    return v;
  }
  std::string text() {
    const std::uint64_t n = uint(4);
    if (!ok || bytes.size() - at < n) return ok = false, std::string();
    std::string s(reinterpret_cast<const char*>(bytes.data() + at), n);
    at += n;
    return s;
  }
};

}  // namespace

std::string cache_root() {
  namespace fs = std::filesystem;
  if (const char* dir = std::getenv("SNAPFIT_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return (fs::path(xdg) / "snapfit").string();
  if (const char* home = std::getenv("HOME"); home && *home) return (fs::path(home) / ".cache" / "snapfit").string();
  return (fs::temp_directory_path() / "snapfit-cache").string();
}

CacheRead read_cache_file(const std::string& path, const std::string& kind, std::uint32_t version,
                          const std::string& key) {
  CacheRead result;
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    result.status = CacheStatus::missing;
    result.reason = "no cache file";
    return result;
  }
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  Reader r{bytes};
  auto corrupt = [&](const std::string& why) {
    result.status = CacheStatus::corrupt;
    result.reason = why;
    return result;
  };
  if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
    return corrupt("not a snapfit cache file (bad magic)");
  r.at = sizeof kMagic;
  const std::uint32_t container = static_cast<std::uint32_t>(r.uint(4));
  if (r.ok && container != kContainerVersion) {
    result.status = CacheStatus::stale;
    result.reason =
        "cache container version " + std::to_string(container) + ", expected " + std::to_string(kContainerVersion);
    return result;
  }
  const std::string file_kind = r.text();
  const std::uint32_t file_version = static_cast<std::uint32_t>(r.uint(4));
  const std::string file_key = r.text();
  const std::uint64_t size = r.uint(8);
  const std::uint64_t checksum = r.uint(8);
  if (!r.ok) return corrupt("truncated header");
  if (file_kind != kind || file_version != version || file_key != key) {
    result.status = CacheStatus::stale;
    result.reason = file_kind != kind ? "written for '" + file_kind + "'"
                    : file_version != version
                        ? "format version " + std::to_string(file_version) + ", expected " + std::to_string(version)
                        : "written for a different key";
    return result;
  }
  if (bytes.size() - r.at != size)
    return corrupt("payload is " + std::to_string(bytes.size() - r.at) + " bytes, header says " + std::to_string(size));
  if (fnv1a64(bytes.data() + r.at, size) != checksum) return corrupt("checksum mismatch");
  result.status = CacheStatus::hit;
  result.payload.assign(bytes.begin() + static_cast<std::ptrdiff_t>(r.at), bytes.end());
  return result;
}

void write_cache_file(const std::string& path, const std::string& kind, std::uint32_t version, const std::string& key,
                      const void* payload, std::size_t payload_size) {
  namespace fs = std::filesystem;
  std::string header(kMagic, sizeof kMagic);
  put_u32(header, kContainerVersion);
  put_text(header, kind);
  put_u32(header, version);
  put_text(header, key);
  put_u64(header, payload_size);
  put_u64(header, fnv1a64(payload, payload_size));

  std::error_code ec;
  const fs::path target(path);
  if (target.has_parent_path()) fs::create_directories(target.parent_path(), ec);
  if (ec) throw Error(path + ": cannot create cache folder: " + ec.message());
  write_file_atomically(path, errno_status([&](std::FILE* f) {
                          return std::fwrite(header.data(), 1, header.size(), f) == header.size() &&
                                 std::fwrite(payload, 1, payload_size, f) == payload_size;
                        }));
}

std::optional<std::vector<unsigned char>> read_cache_payload(const std::string& path, const std::string& kind,
                                                             std::uint32_t version, const std::string& key,
                                                             const std::string& what,
                                                             const std::function<void(const std::string&)>& note) {
  CacheRead entry = read_cache_file(path, kind, version, key);
  if (entry.status == CacheStatus::hit) return std::move(entry.payload);
  if (entry.status != CacheStatus::missing && note)
    note(what + " " + path + " is " + (entry.status == CacheStatus::corrupt ? "corrupt" : "stale") + " (" +
         entry.reason + "); recomputing");
  return std::nullopt;
}

}  // namespace snapfit
