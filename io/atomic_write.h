#pragma once
// Every file snapfit writes goes through here: into a temporary file beside the target,
// flushed and synced, then renamed onto it, so a reader sees the old file or the new
// one and never half of one (no data loss on a crash or a full disk).
#include <cstdio>
#include <functional>
#include <string>

#include "snapfit/export.h"  // write_text_file, the whole file at once

namespace snapfit {

// `body` writes the content to the open temporary and returns "" on success or the
// reason it failed. On any failure the temporary is removed and snapfit::Error
// "<path>: cannot write file: <reason>" is thrown. The temporary's name
// ("<path>.tmp.<pid>.<n>") is unique per call, so concurrent writers of one path in
// one process do not collide (the last rename wins).
void write_file_atomically(const std::string& path, const std::function<std::string(std::FILE*)>& body);

// Adapts a writer that returns false on failure (with errno set) to the form above.
std::function<std::string(std::FILE*)> errno_status(std::function<bool(std::FILE*)> body);

}  // namespace snapfit
