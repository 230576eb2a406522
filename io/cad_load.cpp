// CAD part import through OpenCASCADE in the import child (io/cad_load.h).
#include "io/cad_load.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <mutex>
#include <sstream>

#include "core/grid.h"
#include "io/face_codec.h"
#include "io/file_error.h"
#include "io/import_child.h"
#include "io/occt_shapes.h"
#include "io/step_units.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kMetresPerMillimetre = 1e-3;  // OpenCASCADE gives shapes in millimetres

std::string number_text(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string solid_list(const std::vector<occt::NamedSolid>& solids) {
  std::string list;
  for (const occt::NamedSolid& s : solids) list += (list.empty() ? "'" : ", '") + s.name + "'";
  return list;
}

const occt::NamedSolid& pick_solid(const std::string& path, const occt::CadFile& file,
                                   const std::optional<std::string>& name) {
  if (name) {
    for (const occt::NamedSolid& s : file.solids)
      if (s.name == *name) return s;
    file_error(path, "no solid named '" + *name + "' (the file's solids: " + solid_list(file.solids) + ")");
  }
  if (file.solids.size() > 1)
    file_error(path, "holds " + std::to_string(file.solids.size()) + " solids (" + solid_list(file.solids) +
                         "); name the one to use (a scene part's cad.solid, MeshFileRequest::solid)");
  return file.solids.front();
}

// The first and last `n` bytes of a file.
std::string file_bytes(const std::string& path, std::uintmax_t size, std::uintmax_t n, bool tail) {
  std::ifstream in(path, std::ios::binary);
  const std::uintmax_t count = std::min(n, size);
  if (tail) in.seekg(static_cast<std::streamoff>(size - count));
  std::string bytes(count, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(count));
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  return bytes;
}

// STEP files (ISO 10303-21) open with "ISO-10303-21;" and close with "END-ISO-10303-21;";
// IGES files are 80-column records that close with the terminate record ("T      1" in
// columns 73-80). A file cut short, or of another kind, is refused here, before a parser sees it.
void check_complete(const std::string& path, CadFormat format, std::uintmax_t size) {
  const char* blank = " \t\r\n";
  std::string tail = file_bytes(path, size, 512, true);
  tail.erase(tail.find_last_not_of(blank) + 1);
  if (format == CadFormat::step) {
    std::string head = file_bytes(path, size, 512, false);
    if (head.rfind("\xEF\xBB\xBF", 0) == 0) head.erase(0, 3);  // a UTF-8 byte order mark
    head.erase(0, head.find_first_not_of(blank));
    const std::string end = "END-ISO-10303-21;";
    if (head.rfind("ISO-10303-21;", 0) != 0)
      file_error(path, "cannot read CAD file: not a STEP file (it does not start with ISO-10303-21;)");
    if (tail.size() < end.size() || tail.compare(tail.size() - end.size(), end.size(), end) != 0)
      file_error(path, "cannot read CAD file: truncated STEP file (it does not end with " + end + ")");
  } else {
    // The terminate record's columns 73-80: 'T' and its sequence number, right-aligned.
    if (tail.size() < 8 || tail[tail.size() - 8] != 'T')
      file_error(path,
                 "cannot read CAD file: truncated or not an IGES file (its last record is not a terminate record)");
  }
}

// The whole import; runs in the import child.
std::string import_cad(const std::string& path, const CadImportOptions& options) {
  return occt::guard_occt(path, [&] {
    if (cad_format(path) == CadFormat::step)
      if (const std::string unit = step_length_unit_problem(path); !unit.empty())
        file_error(path, "cannot read CAD file: " + unit);
    const occt::CadFile file = occt::read_cad_file(path);
    const occt::NamedSolid& chosen = pick_solid(path, file, options.solid);
    const double scale = kMetresPerMillimetre / options.metres_per_unit * options.scale;  // mm -> output units
    const occt::SolidGeometry exact = occt::solid_geometry(chosen.solid);

    CadFacts facts;
    facts.format = file.format;
    facts.file_unit = file.file_unit;
    for (const occt::NamedSolid& s : file.solids) facts.solids.push_back(s.name);
    facts.solid = chosen.name;
    if (options.linear_deflection) {
      facts.linear_deflection = *options.linear_deflection;
      facts.deflection_source = "given";
    } else {
      const Eigen::AlignedBox3d box(Eigen::Vector3d(exact.box[0], exact.box[1], exact.box[2]) * scale,
                                    Eigen::Vector3d(exact.box[3], exact.box[4], exact.box[5]) * scale);
      const double spacing = common_spacing(options.grid, {box});
      facts.linear_deflection = kDefaultDeflectionPerSpacing * spacing;
      facts.deflection_source = number_text(kDefaultDeflectionPerSpacing) + " x grid spacing " + number_text(spacing) +
                                (options.grid.spacing ? "" : " (the grid's resolution over this solid)");
    }
    facts.angular_deflection_deg = options.angular_deflection_deg;
    occt::Tessellation t;
    try {
      t = occt::tessellate_solid(chosen.solid, facts.linear_deflection / scale,
                                 options.angular_deflection_deg * kPi / 180.0, scale, path);
    } catch (const Error& e) {
      // A part far larger than intended (a file in metres read as such, a wrong scale)
      // asks for more triangles than the mesher makes: say how large it came out.
      std::ostringstream size;
      size << e.what() << " (the solid spans " << (exact.box[3] - exact.box[0]) * scale << " x "
           << (exact.box[4] - exact.box[1]) * scale << " x " << (exact.box[5] - exact.box[2]) * scale << " "
           << options.units << " from the file's length unit " << file.file_unit << " and scale " << options.scale
           << ", meshed to within " << facts.linear_deflection << " " << options.units
           << "; if the part should be smaller, its file's unit or the scene's \"scale\" is wrong)";
      throw Error(size.str());
    }
    if (t.mesh.triangles.empty()) file_error(path, "cannot read CAD file: the tessellation holds no triangles");
    facts.faces = t.faces;
    facts.triangles = t.mesh.triangles.size();
    const occt::SolidFaces faces = occt::analytic_faces_of(chosen.solid, scale);
    for (const AnalyticFace& f : faces.faces)
      ++(f.kind == FaceKind::plane      ? facts.planes
         : f.kind == FaceKind::cylinder ? facts.cylinders
         : f.kind == FaceKind::cone     ? facts.cones
                                        : facts.tori);
    facts.other_faces = faces.other;
    facts.exact_volume = exact.volume * scale * scale * scale;
    facts.exact_area = exact.area * scale * scale;
    return encode_mesh(t.mesh) + encode_faces(faces.faces) + cad_facts_json(facts);
  });
}

void check_options(const std::string& path, const CadImportOptions& o) {
  const auto positive = [&](double v, const char* what) {
    if (!(std::isfinite(v) && v > 0))
      file_error(path, std::string(what) + " must be finite and > 0 (got " + number_text(v) + ")");
  };
  positive(o.metres_per_unit, "the unit's size in metres");
  positive(o.scale, "scale");
  if (o.linear_deflection) positive(*o.linear_deflection, "the linear deflection");
  if (!(o.angular_deflection_deg > 0 && o.angular_deflection_deg <= 90))
    file_error(path,
               "the angular deflection must be in (0, 90] degrees (got " + number_text(o.angular_deflection_deg) + ")");
  if (o.solid && o.solid->empty()) file_error(path, "the solid's name must not be empty");
  if (!o.linear_deflection) {
    if (o.grid.spacing)
      positive(*o.grid.spacing, "the grid spacing");
    else if (!o.grid.resolution || *o.grid.resolution < 2)
      file_error(path,
                 "a CAD part needs a linear deflection, or a grid spacing or a resolution of at least 2 to tie it to");
  }
}

}  // namespace

CadMesh load_cad_mesh(const std::string& path, const CadImportOptions& options) {
  if (!is_cad_file(path)) file_error(path, "not a STEP or IGES file name (expected .step, .stp, .iges or .igs)");
  check_options(path, options);
  const std::uintmax_t file_size = check_import_file(path);
  check_complete(path, cad_format(path), file_size);
  // OpenCASCADE's readers share global state: imports in this process (with
  // SNAPFIT_IMPORT_MEMORY_MIB=inprocess) take turns; each import child has its own.
  static std::mutex in_process;
  const std::string bytes = run_import(path, file_size, "CAD file", [&] {
    const std::lock_guard<std::mutex> lock(in_process);
    return import_cad(path, options);
  });
  CadMesh out;
  std::size_t used = 0;
  out.mesh = decode_mesh(path, bytes, &used);
  std::size_t faces_used = 0;
  out.faces = decode_faces(path, std::string_view(bytes).substr(used), faces_used);
  used += faces_used;
  try {
    out.facts = cad_facts_from_json(bytes.substr(used));
  } catch (const Error& e) {
    file_error(path, std::string("cannot read CAD file: malformed reply from the importer: ") + e.what());
  }
  return out;
}

}  // namespace snapfit
