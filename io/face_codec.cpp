// Analytic faces to bytes and back (io/face_codec.h): the face count, then per face its
// kind, the plane's and the revolution's numbers and the excluded discs, through
// io/cache_payload.h's bounds-checked reader.
#include "io/face_codec.h"

#include "io/cache_payload.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

const char* kind_name(FaceKind kind) {
  switch (kind) {
    case FaceKind::plane:
      return "cad plane";
    case FaceKind::cylinder:
      return "cad cylinder";
    case FaceKind::cone:
      return "cad cone";
    case FaceKind::torus:
      return "cad torus";
  }
  return "cad face";
}

}  // namespace

std::string encode_faces(const std::vector<AnalyticFace>& faces) {
  PayloadWriter w;
  w.put<std::uint64_t>(faces.size());
  for (const AnalyticFace& f : faces) {
    w.put(static_cast<std::uint8_t>(f.kind));
    for (const Eigen::Vector3d* v : {&f.origin, &f.axis, &f.lo, &f.hi}) w.put_vector3(*v);
    for (double x : {f.r_in, f.r_out, f.a0, f.a1, f.r0, f.r1, f.ac, f.rc}) w.put(x);
    w.put<std::uint8_t>(f.material_inside ? 1 : 0);
    w.put<std::uint64_t>(f.holes.size());
    for (const ExcludedDisc& h : f.holes) {
      w.put_vector3(h.centre);
      w.put(h.radius);
    }
  }
  return std::string(w.bytes.begin(), w.bytes.end());
}

std::vector<AnalyticFace> decode_faces(const std::string& path, std::string_view bytes, std::size_t& used) {
  const std::vector<unsigned char> data(bytes.begin(), bytes.end());
  PayloadReader r{data};
  const auto malformed = [&] {
    return Error(path + ": cannot read CAD file: malformed analytic faces in the importer's reply");
  };
  const std::uint64_t n = r.get<std::uint64_t>();
  if (!r.ok || n > data.size()) throw malformed();
  std::vector<AnalyticFace> faces(n);
  for (AnalyticFace& f : faces) {
    const auto kind = r.get<std::uint8_t>();
    if (kind > static_cast<std::uint8_t>(FaceKind::torus)) throw malformed();
    f.kind = static_cast<FaceKind>(kind);
    f.name = kind_name(f.kind);
    for (Eigen::Vector3d* v : {&f.origin, &f.axis, &f.lo, &f.hi}) *v = r.get_vector3<Eigen::Vector3d>();
    for (double* x : {&f.r_in, &f.r_out, &f.a0, &f.a1, &f.r0, &f.r1, &f.ac, &f.rc}) *x = r.get<double>();
    f.material_inside = r.get<std::uint8_t>() != 0;
    const std::uint64_t holes = r.get<std::uint64_t>();
    if (!r.ok || holes > data.size()) throw malformed();
    f.holes.resize(holes);
    for (ExcludedDisc& h : f.holes) {
      h.centre = r.get_vector3<Eigen::Vector3d>();
      h.radius = r.get<double>();
    }
    if (!r.ok) throw malformed();
  }
  used = r.at;
  return faces;
}

}  // namespace snapfit
