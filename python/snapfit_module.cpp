// The Python module `snapfit` (import snapfit): a thin layer over the public C++ API
// (include/snapfit) with numpy arrays in and out. Poses are (N, 7) arrays, position then
// unit quaternion (w, x, y, z), or (N, 3) positions for translation-only scenes; results
// are arrays of N rows. snapfit::Error becomes snapfit.Error.
#include <cmath>
#include <memory>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <string>
#include <vector>

#include "snapfit/assembly.h"
#include "snapfit/error.h"
#include "snapfit/query.h"
#include "snapfit/scene.h"

namespace py = pybind11;
using namespace snapfit;

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

Interpolation interpolation_named(const std::string& name) {
  if (name == "tricubic") return Interpolation::tricubic;
  if (name == "trilinear") return Interpolation::trilinear;
  throw py::value_error("interpolation must be 'tricubic' or 'trilinear', not '" + name + "'");
}

// Rows of (N, 7) [x, y, z, qw, qx, qy, qz] or (N, 3) [x, y, z]; a single row may be 1-D.
// A row that is not finite, or whose quaternion is not of unit length, is refused by
// index: the engine would answer it with zeros and a flag, which a script would miss.
std::vector<Pose> poses_from(const Array& a, bool translation_only) {
  if (a.ndim() != 1 && a.ndim() != 2)
    throw py::value_error("poses must be an (N, 7) or (N, 3) array, not " + std::to_string(a.ndim()) + "-D");
  const py::ssize_t n = a.ndim() == 1 ? 1 : a.shape(0), width = a.ndim() == 1 ? a.shape(0) : a.shape(1);
  if (width != 7 && width != 3)
    throw py::value_error("poses must have 7 columns (x, y, z, qw, qx, qy, qz) or 3 (x, y, z), not " +
                          std::to_string(width));
  if (width == 3 && !translation_only)
    throw py::value_error("this engine turns part 2: poses need 7 columns (x, y, z, qw, qx, qy, qz)");
  const double* v = a.data();
  std::vector<Pose> poses(static_cast<std::size_t>(n));
  for (py::ssize_t i = 0; i < n; ++i) {
    const double* r = v + i * width;
    for (py::ssize_t k = 0; k < width; ++k)
      if (!std::isfinite(r[k])) throw py::value_error("pose " + std::to_string(i) + " is not finite");
    Pose& p = poses[static_cast<std::size_t>(i)];
    p.translation = Eigen::Vector3d(r[0], r[1], r[2]);
    if (width == 7) {
      p.rotation = Eigen::Quaterniond(r[3], r[4], r[5], r[6]);
      const double norm = p.rotation.norm();
      if (std::abs(norm - 1) > 1e-6)
        throw py::value_error("pose " + std::to_string(i) + ": the quaternion has length " + std::to_string(norm) +
                              ", not 1");
    }
  }
  return poses;
}

// E (N,), F (N, 3), T (N, 3), their error estimates (N, 3: energy, |force|, |torque|), the
// flags (N,) and m' per row, as a dict of arrays.
py::dict results_dict(const std::vector<QueryResult>& results) {
  const py::ssize_t n = static_cast<py::ssize_t>(results.size());
  py::array_t<double> energy(n), force({n, py::ssize_t(3)}), torque({n, py::ssize_t(3)}), estimate({n, py::ssize_t(3)});
  py::array_t<std::uint32_t> flags(n);
  py::array_t<std::uint64_t> modes(n);
  auto e = energy.mutable_unchecked<1>();
  auto f = force.mutable_unchecked<2>();
  auto t = torque.mutable_unchecked<2>();
  auto s = estimate.mutable_unchecked<2>();
  auto g = flags.mutable_unchecked<1>();
  auto m = modes.mutable_unchecked<1>();
  for (py::ssize_t i = 0; i < n; ++i) {
    const QueryResult& r = results[static_cast<std::size_t>(i)];
    e(i) = r.energy;
    for (int k = 0; k < 3; ++k) f(i, k) = r.force[k], t(i, k) = r.torque[k];
    s(i, 0) = r.error_estimate.energy, s(i, 1) = r.error_estimate.force, s(i, 2) = r.error_estimate.torque;
    g(i) = r.flags;
    m(i) = r.modes;
  }
  py::dict d;
  d["energy"] = energy, d["force"] = force, d["torque"] = torque, d["error_estimate"] = estimate;
  d["flags"] = flags, d["modes"] = modes;
  return d;
}

}  // namespace

PYBIND11_MODULE(_snapfit, m) {
  m.doc() = "snapfit: geometric energy, force and torque between two rigid parts (seed 000's method).";
  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      error(e.what());
    }
  });

  py::class_<Scene>(m, "Scene", "An assembly scene: two parts, the grid, the trajectory (docs/scenes.md).")
      .def_property_readonly("name", [](const Scene& s) { return s.name; })
      .def_property_readonly("units", [](const Scene& s) { return s.units; })
      .def("to_json", &scene_to_json, "The scene as JSON text (the scene file's schema).")
      .def("__repr__", [](const Scene& s) { return "<snapfit.Scene '" + s.name + "'>"; });

  m.def("load_scene", &load_scene, py::arg("path"),
        "Reads a scene file; raises snapfit.Error naming the file or field that is wrong.");
  m.def("_parse_scene", &parse_scene, py::arg("json_text"), py::arg("origin"));

  py::class_<QueryEngine, std::unique_ptr<QueryEngine>>(m, "QueryEngine",
                                                        "The per-frame engine of an assembly on its device.")
      .def_property_readonly("variant", [](const QueryEngine& q) { return variant_name(q.variant()); })
      .def_property_readonly("translation_only", [](const QueryEngine& q) { return q.variant().translation_only; })
      .def_property_readonly("max_modes", &QueryEngine::max_modes)
      .def_property(
          "modes", &QueryEngine::modes, [](QueryEngine& q, std::size_t m) { q.set_modes(m); },
          "m', the Fourier modes summed (clamped to [1, max_modes]).")
      .def(
          "query",
          [](QueryEngine& q, const Array& poses) {
            const std::vector<Pose> p = poses_from(poses, q.variant().translation_only);
            std::vector<QueryResult> results(p.size());
            {
              py::gil_scoped_release released;
              q.query_batch(p.data(), p.size(), results.data());
            }
            return results_dict(results);
          },
          py::arg("poses"),
          "E, F and T at each pose of an (N, 7) array [x, y, z, qw, qx, qy, qz] (part 2 in part 1's frame)\n"
          "or (N, 3) for a translation-only scene. Returns a dict of arrays: energy (N,), force (N, 3),\n"
          "torque (N, 3), error_estimate (N, 3), flags (N,), modes (N,).");

  py::class_<Assembly>(m, "Assembly", "A scene's parts, fields and spectra on one OpenCL device.")
      .def(py::init([](const Scene& scene, const std::string& device, bool use_cache) {
             AssemblyOptions o;
             o.device = device;
             o.use_cache = use_cache;
             py::gil_scoped_release released;
             return std::make_unique<Assembly>(scene, o);
           }),
           py::arg("scene"), py::arg("device") = "", py::arg("use_cache") = true)
      .def_property_readonly("scene", &Assembly::scene, py::return_value_policy::reference_internal)
      .def_property_readonly("device_name", &Assembly::device_name)
      .def_property_readonly("spacing", &Assembly::spacing)
      .def_property_readonly("fft_dims", &Assembly::fft_dims)
      .def(
          "query_engine",
          [](const Assembly& a, const std::string& interpolation) {
            return a.make_query_engine(a.query_variant(interpolation_named(interpolation)));
          },
          py::arg("interpolation") = "tricubic",
          "A query engine for the scene's variant ('tricubic' or 'trilinear' rotation interpolation).");
}
