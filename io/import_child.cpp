// Shared by the importers: file checks, the import child and its reply (io/import_child.h).
#include "io/import_child.h"

#include <Eigen/Core>
#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <new>
#include <optional>
#include <system_error>
#include <unistd.h>

#include "io/file_error.h"
#include "io/isolated_import.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

namespace fs = std::filesystem;

// Limits of the import child. Malformed files can make an importer allocate gigabytes
// from a few kilobytes (fuzzed .x and .dae files in Assimp); on valid files Assimp's
// address space grows up to about 35x the file size, linearly, with a few seconds of CPU
// per million triangles (perf/bench_mesh_import measures both; docs/stability.md has the
// figures).
std::optional<ChildLimits> import_limits(const std::string& path, std::uintmax_t file_size) {
  const std::uint64_t file_mib = (file_size + (1u << 20) - 1) >> 20;
  ChildLimits limits;
  limits.memory_mib = 1024 + 64 * file_mib;
  const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGESIZE);
  if (pages > 0 && page_size > 0)
    limits.memory_mib =
        std::min<std::uint64_t>(limits.memory_mib, (static_cast<std::uint64_t>(pages) * page_size >> 20) / 2);
  limits.seconds = static_cast<unsigned>(std::min<std::uint64_t>(60 + file_mib, 1u << 30));
  limits.wall_seconds = 3.0 * limits.seconds;  // a loaded machine, or a child that waits
  if (const char* env = std::getenv("SNAPFIT_IMPORT_MEMORY_MIB")) {
    const std::string v = env;
    const bool whole = !v.empty() && v.size() <= 9 && v.find_first_not_of("0123456789") == std::string::npos;
    if (!(v == "inprocess" || whole))
      file_error(path, "SNAPFIT_IMPORT_MEMORY_MIB must be a whole number of MiB, 0 or 'inprocess' (got '" + v + "')");
    if (v == "inprocess" || std::stoull(v) == 0) return std::nullopt;
    limits.memory_mib = std::stoull(v);
  }
  return limits;
}

}  // namespace

std::uintmax_t check_import_file(const std::string& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (ec || !fs::exists(st)) {
    if (ec && ec != std::errc::no_such_file_or_directory) file_error(path, "cannot access file: " + ec.message());
    file_error(path, "file not found");
  }
  if (!fs::is_regular_file(st)) file_error(path, "not a regular file");
  const auto size = fs::file_size(path, ec);
  if (ec) file_error(path, "cannot read file size: " + ec.message());
  if (size == 0) file_error(path, "file is empty");
  std::ifstream probe(path, std::ios::binary);
  if (!probe) file_error(path, "file is not readable");
  return size;
}

std::string run_import(const std::string& path, std::uintmax_t file_size, const std::string& what,
                       const std::function<std::string()>& work) {
  const std::string cannot = "cannot read " + what + ": ";
  const std::optional<ChildLimits> limits = import_limits(path, file_size);
  if (!limits) {
    try {
      return work();
    } catch (const std::bad_alloc&) {
      file_error(path, cannot + "out of memory (std::bad_alloc)");
    }
  }

  ChildResult r = run_in_child(work, *limits);
  switch (r.status) {
    case ChildResult::Status::ok:
      return std::move(r.bytes);
    case ChildResult::Status::error:
      throw Error(r.bytes);  // the child's snapfit::Error, unchanged
    case ChildResult::Status::exception:
      file_error(path, cannot + r.bytes);
    case ChildResult::Status::out_of_memory:
      file_error(path, cannot + "the importer exceeded its memory limit of " + std::to_string(limits->memory_mib) +
                           " MiB (SNAPFIT_IMPORT_MEMORY_MIB sets it)");
    case ChildResult::Status::crashed:
      file_error(
          path, cannot + "the importer crashed (signal " + std::to_string(r.signal) + ", " + strsignal(r.signal) + ")");
    case ChildResult::Status::timed_out:
      file_error(path, cannot + "the importer took longer than " + std::to_string(limits->seconds) + " s");
    case ChildResult::Status::bad_reply:
      break;
  }
  file_error(path, cannot + "the importer " + r.bytes);
}

// Vertex and triangle counts (uint64), then the vertices' doubles and the triangles'
// ints as they lie in memory.
static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double) && sizeof(Eigen::Vector3i) == 3 * sizeof(int));

std::string encode_mesh(const Mesh& m) {
  const std::uint64_t counts[2] = {m.vertices.size(), m.triangles.size()};
  const std::size_t vb = m.vertices.size() * sizeof(Eigen::Vector3d), tb = m.triangles.size() * sizeof(Eigen::Vector3i);
  std::string out(sizeof counts + vb + tb, '\0');
  std::memcpy(out.data(), counts, sizeof counts);
  if (vb > 0) std::memcpy(out.data() + sizeof counts, m.vertices.data(), vb);
  if (tb > 0) std::memcpy(out.data() + sizeof counts + vb, m.triangles.data(), tb);
  return out;
}

Mesh decode_mesh(const std::string& path, std::string_view bytes, std::size_t* used) {
  std::uint64_t counts[2] = {0, 0};
  if (bytes.size() >= sizeof counts) std::memcpy(counts, bytes.data(), sizeof counts);
  const std::uint64_t max = bytes.size();  // bounds the counts before they are multiplied
  const auto size = [&] {
    return sizeof counts + counts[0] * sizeof(Eigen::Vector3d) + counts[1] * sizeof(Eigen::Vector3i);
  };
  if (bytes.size() < sizeof counts || counts[0] > max || counts[1] > max ||
      (used ? bytes.size() < size() : bytes.size() != size()))
    file_error(path,
               "cannot read mesh: malformed reply from the importer (" + std::to_string(bytes.size()) + " bytes)");
  Mesh m;
  m.vertices.resize(counts[0]);
  m.triangles.resize(counts[1]);
  const std::size_t vb = m.vertices.size() * sizeof(Eigen::Vector3d), tb = m.triangles.size() * sizeof(Eigen::Vector3i);
  if (vb > 0) std::memcpy(static_cast<void*>(m.vertices.data()), bytes.data() + sizeof counts, vb);
  if (tb > 0) std::memcpy(static_cast<void*>(m.triangles.data()), bytes.data() + sizeof counts + vb, tb);
  if (used) *used = sizeof counts + vb + tb;
  return m;
}

}  // namespace snapfit
