#pragma once
// Small helpers shared by the test files: temporary folders, file bytes, commands, the
// message of an expected error, base64.
#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <random>
#include <string>
#include <sys/wait.h>
#include <vector>

#include "snapfit/error.h"

namespace snapfit::test {

inline constexpr double kPi = 3.14159265358979323846;

// A fresh folder under the system temp dir, removed when the object goes away.
struct TempDir {
  std::filesystem::path path;
  TempDir() {
    std::random_device rd;
    path = std::filesystem::temp_directory_path() / ("snapfit-test-" + std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);
  }
  std::string file(const std::string& name) const { return (path / name).string(); }
};

// Sets (or, given nullptr, unsets) an environment variable; restores the old value after.
struct EnvScope {
  std::string name;
  std::optional<std::string> previous;
  EnvScope(const std::string& var, const char* value) : name(var) {
    if (const char* old = std::getenv(name.c_str())) previous = old;
    if (value)
      ::setenv(name.c_str(), value, 1);
    else
      ::unsetenv(name.c_str());
  }
  EnvScope(const EnvScope&) = delete;
  EnvScope& operator=(const EnvScope&) = delete;
  ~EnvScope() {
    if (previous)
      ::setenv(name.c_str(), previous->c_str(), 1);
    else
      ::unsetenv(name.c_str());
  }
};

// Points SNAPFIT_CACHE_DIR (io/cache_file.h cache_root()) at a fresh temporary folder;
// restores the old value after.
struct CacheDirScope {
  TempDir dir;
  EnvScope env{"SNAPFIT_CACHE_DIR", dir.path.string().c_str()};
  std::filesystem::path folder(const std::string& name) const { return dir.path / name; }
};

inline std::vector<char> read_bytes(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  return std::vector<char>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

inline void write_bytes(const std::string& file, const std::vector<char>& bytes) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

inline void write_text(const std::string& file, const std::string& text) {
  std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
}

// Runs a shell command; its exit status and its output (stdout, with stderr too when
// `with_stderr`).
struct Command {
  int status = -1;
  std::string output;
};

inline Command run_command(const std::string& command, bool with_stderr = true) {
  Command c;
  std::FILE* p = ::popen((command + (with_stderr ? " 2>&1" : " 2>/dev/null")).c_str(), "r");
  if (p == nullptr) return c;
  std::array<char, 4096> buffer{};
  std::size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), p)) > 0) c.output.append(buffer.data(), n);
  const int raw = ::pclose(p);
  c.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
  return c;
}

// Decodes RFC 4648 base64 (padding ends it): the reference for report/page_encoding.h.
inline std::vector<unsigned char> decode_base64(const std::string& text) {
  std::vector<unsigned char> out;
  unsigned value = 0;
  int bits = 0;
  for (char c : text) {
    int v;
    if (c >= 'A' && c <= 'Z')
      v = c - 'A';
    else if (c >= 'a' && c <= 'z')
      v = c - 'a' + 26;
    else if (c >= '0' && c <= '9')
      v = c - '0' + 52;
    else if (c == '+')
      v = 62;
    else if (c == '/')
      v = 63;
    else
      break;
    value = (value << 6) | unsigned(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      out.push_back(static_cast<unsigned char>((value >> bits) & 255));
    }
  }
  return out;
}

// Base64 of little-endian float32 values (report/page_encoding.h) as floats.
inline std::vector<float> decode_float32_base64(const std::string& text) {
  const std::vector<unsigned char> bytes = decode_base64(text);
  std::vector<float> out(bytes.size() / 4);
  for (std::size_t i = 0; i < out.size(); ++i) std::memcpy(&out[i], bytes.data() + 4 * i, 4);
  return out;
}

// The message of the snapfit::Error that `f` throws, or "no error".
inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace snapfit::test
