#include "io/atomic_write.h"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <unistd.h>

#include "snapfit/error.h"

namespace snapfit {

void write_file_atomically(const std::string& path, const std::function<std::string(std::FILE*)>& body) {
  static std::atomic<unsigned> counter{0};
  const std::string tmp =
      path + ".tmp." + std::to_string(static_cast<long>(::getpid())) + "." + std::to_string(counter.fetch_add(1));
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  if (f == nullptr) throw Error(path + ": cannot create file: " + std::strerror(errno));
  std::string problem = body(f);
  if (problem.empty() && (std::fflush(f) != 0 || ::fsync(::fileno(f)) != 0)) problem = std::strerror(errno);
  if (std::fclose(f) != 0 && problem.empty()) problem = std::strerror(errno);
  if (problem.empty() && std::rename(tmp.c_str(), path.c_str()) != 0) problem = std::strerror(errno);
  if (!problem.empty()) {
    std::remove(tmp.c_str());
    throw Error(path + ": cannot write file: " + problem);
  }
}

void write_text_file(const std::string& path, const std::string& text) {
  write_file_atomically(path, [&](std::FILE* f) {
    return std::fwrite(text.data(), 1, text.size(), f) == text.size() ? std::string() : std::string("short write");
  });
}

std::function<std::string(std::FILE*)> errno_status(std::function<bool(std::FILE*)> body) {
  return [body = std::move(body)](std::FILE* f) -> std::string {
    errno = 0;
    return body(f) ? std::string() : std::strerror(errno != 0 ? errno : EIO);
  };
}

}  // namespace snapfit
