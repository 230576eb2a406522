// Mesh import through Assimp (io/mesh_load.h).
#include "io/mesh_load.h"

#include <Eigen/Core>
#include <Eigen/LU>  // determinant
#include <algorithm>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <new>
#include <sstream>
#include <utility>
#include <vector>

#include "io/file_error.h"
#include "io/import_child.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

namespace fs = std::filesystem;

// Whitespace-separated tokens in the first 4 KiB of a file, '#' comments skipped.
std::vector<std::string> leading_tokens(const std::string& path, std::size_t count) {
  std::ifstream in(path, std::ios::binary);
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  std::istringstream lines(head);
  std::vector<std::string> tokens;
  std::string line;
  while (tokens.size() < count && std::getline(lines, line)) {
    std::istringstream words(line.substr(0, line.find('#')));
    std::string w;
    while (tokens.size() < count && words >> w) tokens.push_back(w);
  }
  return tokens;
}

bool is_count(const std::string& s) {
  return !s.empty() && s.size() <= 19 && s.find_first_not_of("0123456789") == std::string::npos;
}

std::string lowercase_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return ext;
}

// OFF headers declare vertex and face counts, and Assimp 5.2 allocates (and constructs)
// that many vertices up front, wrapping counts above 2^32: the regression file
// invalid/OutOfMemory.off makes it touch ~16 GB. Every vertex or face line takes at
// least 2 bytes ("0\n"), so counts the file cannot hold are rejected before import.
void check_off_counts(const std::string& path, std::uintmax_t file_size) {
  const std::vector<std::string> t = leading_tokens(path, 4);
  if (t.empty()) return;
  std::size_t first = 0;  // index of the vertex count
  // Header keyword: [ST][C][N][4][n]OFF, then (with 'n') the dimension, then the counts.
  const std::string& k = t[0];
  if (k.size() >= 3 && k.compare(k.size() - 3, 3, "OFF") == 0 && k.find_first_not_of("STCN4nOF") == std::string::npos) {
    first = (k.find('n') != std::string::npos) ? 2 : 1;
  } else if (lowercase_extension(path) != ".off" || !is_count(k)) {
    return;  // not OFF; headerless OFF starts with the counts
  }
  if (t.size() < first + 2 || !is_count(t[first]) || !is_count(t[first + 1])) return;
  const unsigned long long vertices = std::stoull(t[first]);
  const unsigned long long faces = std::stoull(t[first + 1]);
  const unsigned long long limit = std::numeric_limits<unsigned int>::max();
  if (vertices > limit || faces > limit || 2 * (vertices + faces) > file_size) {
    std::ostringstream msg;
    msg << "cannot read mesh: OFF header declares " << vertices << " vertices and " << faces << " faces, more than the "
        << file_size << "-byte file can hold";
    file_error(path, msg.str());
  }
}

// PLY (found by truncating valid files): Debian's Assimp 5.2 loops forever on a
// PLY file cut inside its header, and aborts (ai_assert in TriangulateProcess) on one
// cut inside its body. So a file that starts with the "ply" magic is walked here first:
// the header must end with end_header, and the body must hold every element it declares
// (binary: list counts read and skipped; ASCII: enough tokens), and every face at least
// 3 indices. Otherwise it is refused.
void check_ply_complete(const std::string& path, std::uintmax_t file_size) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  if (!std::getline(in, line)) return;
  if (!line.empty() && line.back() == '\r') line.pop_back();
  if (line != "ply") return;  // not PLY
  struct Property {
    int size = 0;        // scalar size, or the item size of a list
    int count_size = 0;  // > 0: a list with a count of this size
  };
  struct Element {
    std::string name;
    unsigned long long count = 0;
    std::vector<Property> properties;
  };
  const auto type_size = [](const std::string& t) {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
    if (t == "double" || t == "float64") return 8;
    return 0;
  };
  std::vector<Element> elements;
  std::string format;
  bool ended = false, unknown_type = false;
  for (int n = 0; n < 100000 && std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "end_header") {
      ended = true;
      break;
    }
    if (key == "format") {
      words >> format;
    } else if (key == "element") {
      Element e;
      std::string count;
      words >> e.name >> count;
      if (!is_count(count)) file_error(path, "cannot read mesh: PLY element '" + e.name + "' has no valid count");
      e.count = std::stoull(count);
      if (e.count > file_size)
        file_error(path, "cannot read mesh: PLY element '" + e.name + "' declares " + count +
                             " entries, more than the " + std::to_string(file_size) + "-byte file can hold");
      elements.push_back(e);
    } else if (key == "property" && !elements.empty()) {
      std::string type;
      words >> type;
      Property prop;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type;
        prop.count_size = type_size(count_type);
        prop.size = type_size(item_type);
        if (prop.count_size == 0 || prop.size == 0) unknown_type = true;
      } else {
        prop.size = type_size(type);
        if (prop.size == 0) unknown_type = true;
      }
      elements.back().properties.push_back(prop);
    }
  }
  if (!ended) file_error(path, "cannot read mesh: truncated PLY header (no end_header line)");
  if (unknown_type) return;  // a property type not known here: leave the body to Assimp
  const bool ascii = format == "ascii";
  const bool big_endian = format == "binary_big_endian";
  if (!ascii && !big_endian && format != "binary_little_endian") return;  // leave it to Assimp
  // Faces with fewer than 3 indices make Assimp's triangulation abort (ai_assert
  // numOut != mNumFaces; found by fuzz/fuzz_mesh).
  const auto check_face = [&](const Element& e, unsigned long long i, unsigned long long items) {
    if (e.name == "face" && items < 3)
      file_error(path, "cannot read mesh: PLY face " + std::to_string(i) + " has " + std::to_string(items) +
                           " vertex indices (at least 3 needed)");
  };
  const auto truncated = [&](const Element& e, unsigned long long i) {
    file_error(path, "cannot read mesh: truncated PLY body (element '" + e.name + "' entry " + std::to_string(i) +
                         " of " + std::to_string(e.count) + " is missing)");
  };
  const std::streamoff body = in.tellg();
  if (body < 0) file_error(path, "cannot read mesh: truncated PLY header");
  std::uintmax_t offset = static_cast<std::uintmax_t>(body);  // binary: bytes walked so far
  for (const Element& e : elements)
    for (unsigned long long i = 0; i < e.count; ++i)
      for (const Property& p : e.properties) {
        unsigned long long items = 1;
        if (ascii) {
          std::string token;
          if (p.count_size > 0) {
            if (!(in >> token)) truncated(e, i);
            items = is_count(token) ? std::stoull(token) : 0;
            check_face(e, i, items);
          }
          for (unsigned long long k = 0; k < items; ++k)
            if (!(in >> token)) truncated(e, i);
          continue;
        }
        if (p.count_size > 0) {
          unsigned char b[8] = {};
          if (offset + p.count_size > file_size) truncated(e, i);
          in.seekg(static_cast<std::streamoff>(offset));
          if (!in.read(reinterpret_cast<char*>(b), p.count_size)) truncated(e, i);
          offset += p.count_size;
          items = 0;
          for (int k = 0; k < p.count_size; ++k)
            items |= static_cast<unsigned long long>(b[big_endian ? p.count_size - 1 - k : k]) << (8 * k);
          check_face(e, i, items);
        }
        if (items > file_size) truncated(e, i);
        offset += items * static_cast<unsigned long long>(p.size);
        if (offset > file_size) truncated(e, i);
      }
}

// DirectX .x files compressed with MSZIP ("xof 0303bzip" / "tzip"): Debian's Assimp 5.2
// crashes (SEGV) inside its decompressor on malformed ones (found by fuzz/fuzz_mesh,
// regression tests/data/fuzz/x_bzip_segv.bin). Compressed .x files are refused here.
void check_x_uncompressed(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char head[16] = {};
  in.read(head, sizeof head);
  if (in.gcount() < 12 || std::string(head, 4) != "xof ") return;
  const std::string format(head + 8, 4);
  if (format == "bzip" || format == "tzip")
    file_error(path, "cannot read mesh: compressed DirectX .x files (format '" + format +
                         "') are not supported; save it as text or binary .x");
}

// Missing, empty or unreadable files (check_import_file), and files Debian's Assimp 5.2
// is known to crash or hang on: say so before Assimp guesses. Returns the file's size.
std::uintmax_t check_input_file(const std::string& path) {
  const std::uintmax_t size = check_import_file(path);
  check_off_counts(path, size);
  check_ply_complete(path, size);
  check_x_uncompressed(path);
  return size;
}

// aiMatrix4x4 is row-major: a1..a4 is the first row.
Eigen::Matrix4d to_eigen(const aiMatrix4x4& m) {
  Eigen::Matrix4d e;
  e << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
  return e;
}

struct Walk {
  const std::string& path;
  const aiScene& scene;
  double scale;
  Mesh& out;
};

// Appends the triangles of one aiMesh, vertices mapped through `transform` (homogeneous).
void append_mesh(const Walk& w, unsigned mesh_index, const Eigen::Matrix4d& transform) {
  const aiMesh& am = *w.scene.mMeshes[mesh_index];
  // A mirroring node transform (det < 0) turns outward normals inward: rewind.
  const bool mirrored = transform.topLeftCorner<3, 3>().determinant() < 0.0;
  // Only vertices used by triangles are copied; -1 = not yet copied.
  std::vector<int> remap(am.mNumVertices, -1);
  for (unsigned f = 0; f < am.mNumFaces; ++f) {
    const aiFace& face = am.mFaces[f];
    if (face.mNumIndices != 3) continue;  // points and lines are not part of a boundary
    Eigen::Vector3i tri;
    for (int k = 0; k < 3; ++k) {
      const unsigned idx = face.mIndices[k];
      if (idx >= am.mNumVertices) {
        std::ostringstream msg;
        msg << "face " << f << " of mesh " << mesh_index << " refers to vertex " << idx << " but the mesh has "
            << am.mNumVertices << " vertices";
        file_error(w.path, msg.str());
      }
      if (remap[idx] < 0) {
        if (w.out.vertices.size() >= static_cast<std::size_t>(std::numeric_limits<int>::max()))
          file_error(w.path, "too many vertices");
        const aiVector3D& v = am.mVertices[idx];
        const Eigen::Vector4d p = transform * Eigen::Vector4d(v.x, v.y, v.z, 1.0);
        Eigen::Vector3d q = p.head<3>() / p.w() * w.scale;
        if (!q.allFinite()) {
          std::ostringstream msg;
          msg << "vertex " << idx << " of mesh " << mesh_index << " ('" << am.mName.C_Str()
              << "') has a non-finite coordinate (" << v.x << ", " << v.y << ", " << v.z << " in file units)";
          file_error(w.path, msg.str());
        }
        remap[idx] = static_cast<int>(w.out.vertices.size());
        w.out.vertices.push_back(q);
      }
      tri[k] = remap[idx];
    }
    if (mirrored) std::swap(tri[1], tri[2]);
    w.out.triangles.push_back(tri);
  }
}

// Depth-first over the node tree; a node's global transform = parent global * local.
void walk_node(const Walk& w, const aiNode& node, const Eigen::Matrix4d& parent) {
  const Eigen::Matrix4d global = parent * to_eigen(node.mTransformation);
  for (unsigned i = 0; i < node.mNumMeshes; ++i) {
    const unsigned mi = node.mMeshes[i];
    if (mi >= w.scene.mNumMeshes || w.scene.mMeshes[mi] == nullptr)
      file_error(w.path, "node '" + std::string(node.mName.C_Str()) + "' refers to a missing mesh");
    append_mesh(w, mi, global);
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c)
    if (node.mChildren[c] != nullptr) walk_node(w, *node.mChildren[c], global);
}

// Assimp's import and the walk over its scene, in this process.
Mesh import_mesh(const std::string& path, double scale) {
  // No aiProcess_FindDegenerates: degenerate triangles are reported, not removed.
  // ValidateDataStructure rejects out-of-range indices and similar broken data.
  const unsigned flags =
      aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType | aiProcess_ValidateDataStructure;
  Assimp::Importer importer;
  const aiScene* scene = nullptr;
  try {
    scene = importer.ReadFile(path, flags);
  } catch (const std::bad_alloc&) {
    throw;  // the import child reports it as its memory limit
  } catch (const std::exception& e) {
    file_error(path, std::string("cannot read mesh: ") + e.what());
  } catch (...) {
    file_error(path, "cannot read mesh: unknown error in the importer");
  }
  if (scene == nullptr) {
    // Assimp catches exceptions itself and keeps only the message (assimp/BaseImporter.h).
    if (std::string(importer.GetErrorString()) == std::bad_alloc().what()) throw std::bad_alloc();
    file_error(path, std::string("cannot read mesh: ") + importer.GetErrorString());
  }

  Mesh mesh;
  if (scene->mRootNode != nullptr) {
    const Walk w{path, *scene, scale, mesh};
    walk_node(w, *scene->mRootNode, Eigen::Matrix4d::Identity());
  }
  if (mesh.triangles.empty()) file_error(path, "contains no triangles");
  return mesh;
}

}  // namespace

Mesh load_mesh(const std::string& path, double scale) {
  if (!std::isfinite(scale) || scale <= 0.0) {
    std::ostringstream msg;
    msg << "scale must be finite and > 0 (got " << scale << ")";
    file_error(path, msg.str());
  }
  const std::uintmax_t file_size = check_input_file(path);
  return decode_mesh(path, run_import(path, file_size, "mesh", [&] { return encode_mesh(import_mesh(path, scale)); }));
}

}  // namespace snapfit
