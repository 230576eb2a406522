// Mesh export (io/mesh_export.h).
#include "io/mesh_export.h"

#include <Eigen/Geometry>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <unistd.h>

#include "io/atomic_write.h"
#include "io/file_error.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

// Indices in range and coordinates finite; otherwise the file would be garbage.
void check_mesh(const Mesh& mesh, const std::string& path) {
  const int n = static_cast<int>(mesh.vertices.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (mesh.triangles[t][k] < 0 || mesh.triangles[t][k] >= n)
        file_error(path, "cannot write: triangle " + std::to_string(t) + " refers to vertex " +
                             std::to_string(mesh.triangles[t][k]) + " of " + std::to_string(n));
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
    if (!mesh.vertices[i].allFinite())
      file_error(path, "cannot write: vertex " + std::to_string(i) + " has a non-finite coordinate");
}

// Little-endian encoders, independent of the host byte order.
void put_u32(unsigned char* p, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
void put_f32(unsigned char* p, float x) {
  std::uint32_t bits;
  static_assert(sizeof bits == sizeof x, "float32 expected");
  std::memcpy(&bits, &x, sizeof bits);
  put_u32(p, bits);
}

}  // namespace

void write_stl(const Mesh& mesh, const std::string& path) {
  check_mesh(mesh, path);
  if (mesh.triangles.size() > std::numeric_limits<std::uint32_t>::max())
    file_error(path, "cannot write: too many triangles for STL");
  write_file_atomically(path, errno_status([&mesh](std::FILE* f) {
                          // The header must not start with "solid", or readers take the file for ASCII STL.
                          unsigned char head[84] = {};
                          const char title[] = "binary STL written by snapfit";
                          std::memcpy(head, title, sizeof title - 1);
                          put_u32(head + 80, static_cast<std::uint32_t>(mesh.triangles.size()));
                          if (std::fwrite(head, 1, sizeof head, f) != sizeof head) return false;
                          for (const auto& tri : mesh.triangles) {
                            const Eigen::Vector3d& a = mesh.vertices[tri[0]];
                            const Eigen::Vector3d& b = mesh.vertices[tri[1]];
                            const Eigen::Vector3d& c = mesh.vertices[tri[2]];
                            Eigen::Vector3d normal = (b - a).cross(c - a);  // right-hand rule: CCW from outside
                            const double len = normal.norm();
                            normal = len > 0.0 ? Eigen::Vector3d(normal / len) : Eigen::Vector3d::Zero();
                            unsigned char rec[50] = {};  // normal, 3 vertices (12 float32), uint16 attribute = 0
                            const Eigen::Vector3d* vs[4] = {&normal, &a, &b, &c};
                            for (int v = 0; v < 4; ++v)
                              for (int k = 0; k < 3; ++k)
                                put_f32(rec + 12 * v + 4 * k, static_cast<float>((*vs[v])[k]));
                            if (std::fwrite(rec, 1, sizeof rec, f) != sizeof rec) return false;
                          }
                          return true;
                        }));
}

void write_obj(const Mesh& mesh, const std::string& path) {
  check_mesh(mesh, path);
  write_file_atomically(path, errno_status([&mesh](std::FILE* f) {
                          if (std::fprintf(f, "# written by snapfit: %zu vertices, %zu triangles\n",
                                           mesh.vertices.size(), mesh.triangles.size()) < 0)
                            return false;
                          for (const auto& v : mesh.vertices)
                            if (std::fprintf(f, "v %.17g %.17g %.17g\n", v.x(), v.y(), v.z()) < 0) return false;
                          for (const auto& t : mesh.triangles)
                            if (std::fprintf(f, "f %d %d %d\n", t[0] + 1, t[1] + 1, t[2] + 1) < 0) return false;
                          return true;
                        }));
}

}  // namespace snapfit
