#pragma once
// What every importer of a part file shares (Assimp for meshes, OpenCASCADE for STEP
// and IGES): the checks on the file before a library sees it, and the run of the
// library in a child process under a memory and time limit (io/isolated_import.h), with
// each way the child can fail turned into one snapfit::Error naming the file.
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include "mesh/mesh.h"

namespace snapfit {

// Missing, not a regular file, empty or unreadable: an Error naming the file. Returns
// the file's size in bytes.
std::uintmax_t check_import_file(const std::string& path);

// Runs `work` (an importer reading `path`, `file_size` bytes) in a child process and
// returns the bytes it returned. The child's limits: 1 GiB + 64x the file size of address
// space (at most half the physical memory), 60 s + 1 s per MiB of file of CPU time and 3x
// that of wall time. SNAPFIT_IMPORT_MEMORY_MIB sets the memory limit in MiB; 0 or
// "inprocess" runs `work` in this process, without limits (for debugging). A
// snapfit::Error thrown by `work` comes back unchanged; running out of memory, crashing
// or taking too long is an Error "<path>: cannot read <what>: ...".
std::string run_import(const std::string& path, std::uintmax_t file_size, const std::string& what,
                       const std::function<std::string()>& work);

// A mesh as bytes, for the import child's reply (one program on both ends), and back.
// decode_mesh throws an Error naming `path` when `bytes` do not hold exactly one mesh;
// given `used`, the mesh may be followed by more bytes, and `used` says where it ends.
std::string encode_mesh(const Mesh& mesh);
Mesh decode_mesh(const std::string& path, std::string_view bytes, std::size_t* used = nullptr);

}  // namespace snapfit
