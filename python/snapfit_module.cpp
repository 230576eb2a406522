// The Python module `snapfit` (import snapfit): a thin layer over the public C++ API
// (include/snapfit) with numpy arrays in and out. Poses are (N, 7) arrays, position then
// unit quaternion (w, x, y, z), or (N, 3) positions for translation-only scenes; results
// are arrays of N rows. snapfit::Error becomes snapfit.Error.
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <string>
#include <vector>

#include "report/run_report.h"
#include "snapfit/accuracy.h"
#include "snapfit/assembly.h"
#include "snapfit/error.h"
#include "snapfit/fields.h"
#include "snapfit/haptic_loop.h"
#include "snapfit/inspect.h"
#include "snapfit/job.h"
#include "snapfit/live.h"
#include "snapfit/query.h"
#include "snapfit/scene.h"
#include "snapfit/search.h"
#include "snapfit/tuning.h"

namespace py = pybind11;
using namespace snapfit;

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// The query strategy by its name (include/snapfit/query.h strategy_named); the exact
// product is remade for each new rotation (a batch of poses has no loop to follow).
QueryVariant variant_named(const Assembly& a, const std::string& name) {
  const std::optional<QueryStrategy> strategy = strategy_named(name);
  if (!strategy) {
    std::string known;
    for (QueryStrategy s : query_strategies()) known += std::string(known.empty() ? "" : ", ") + strategy_name(s);
    throw py::value_error("strategy must be one of " + known + ", not '" + name + "'");
  }
  const QueryVariant v = a.query_variant(Interpolation::tricubic);
  if (v.translation_only && strategy != QueryStrategy::tricubic)
    throw py::value_error("a translation-only scene has only its lines: no '" + name + "'");
  return with_strategy(v, *strategy, ProductUpdate::each_query);
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

// An (N, 3) array of one Vector3d member per row.
template <typename Row, typename Get>
py::array_t<double> rows3(const std::vector<Row>& rows, Get get) {
  py::array_t<double> a({static_cast<py::ssize_t>(rows.size()), py::ssize_t(3)});
  auto v = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Eigen::Vector3d x = get(rows[i]);
    for (int k = 0; k < 3; ++k) v(static_cast<py::ssize_t>(i), k) = x[k];
  }
  return a;
}

template <typename Row, typename Get>
py::array_t<double> column(const std::vector<Row>& rows, Get get) {
  py::array_t<double> a(static_cast<py::ssize_t>(rows.size()));
  auto v = a.mutable_unchecked<1>();
  for (std::size_t i = 0; i < rows.size(); ++i) v(static_cast<py::ssize_t>(i)) = static_cast<double>(get(rows[i]));
  return a;
}

// The tuning sweep: m' and its p50/p99/max as arrays, the chosen m' and the file.
py::dict tuning_dict(const TuningResult& t) {
  py::dict d;
  d["modes"] = column(t.points, [](const TimingPoint& p) { return p.modes; });
  d["p50_ms"] = column(t.points, [](const TimingPoint& p) { return p.p50_ms; });
  d["p99_ms"] = column(t.points, [](const TimingPoint& p) { return p.p99_ms; });
  d["max_ms"] = column(t.points, [](const TimingPoint& p) { return p.max_ms; });
  d["chosen_modes"] = t.chosen_modes;
  d["fits"] = t.fits;
  d["budget_ms"] = t.budget_ms;
  d["margin"] = t.margin;
  d["file"] = t.file;
  return d;
}

// The loop's log, one row a frame: times, part 2's pose (N, 7), energy, the wrench sent
// (N, 3 each), m', flags and misses.
py::dict loop_dict(const LoopReport& loop) {
  const std::vector<FrameRecord>& log = loop.log;
  py::array_t<double> pose({static_cast<py::ssize_t>(log.size()), py::ssize_t(7)});
  auto p = pose.mutable_unchecked<2>();
  for (std::size_t i = 0; i < log.size(); ++i) {
    const Pose& x = log[i].part;
    const double row[7] = {x.translation.x(), x.translation.y(), x.translation.z(), x.rotation.w(),
                           x.rotation.x(),    x.rotation.y(),    x.rotation.z()};
    for (int k = 0; k < 7; ++k) p(static_cast<py::ssize_t>(i), k) = row[k];
  }
  py::dict d;
  d["time_s"] = column(log, [](const FrameRecord& f) { return f.time_s; });
  d["frame_ms"] = column(log, [](const FrameRecord& f) { return f.frame_ms; });
  d["part_pose"] = pose;
  d["energy"] = column(log, [](const FrameRecord& f) { return f.energy; });
  d["force_sent"] = rows3(log, [](const FrameRecord& f) { return f.sent.force; });
  d["torque_sent"] = rows3(log, [](const FrameRecord& f) { return f.sent.torque; });
  d["contact_depth"] = column(log, [](const FrameRecord& f) { return f.contact_depth; });
  d["modes"] = column(log, [](const FrameRecord& f) { return f.modes; });
  d["flags"] = column(log, [](const FrameRecord& f) { return f.flags; });
  d["missed"] = column(log, [](const FrameRecord& f) { return f.missed ? 1.0 : 0.0; });
  d["frames"] = loop.frames;
  d["misses"] = loop.misses;
  d["measured_rate_hz"] = loop.measured_rate_hz;
  return d;
}

// A field on its grid as a (nz, ny, nx) array: the grid's i runs fastest (include/snapfit/grid.h).
py::object grid_array(const GridSpec& grid, const std::vector<float>& values) {
  if (values.empty()) return py::none();
  py::array_t<float> a({static_cast<py::ssize_t>(grid.dims.z()), static_cast<py::ssize_t>(grid.dims.y()),
                        static_cast<py::ssize_t>(grid.dims.x())});
  std::copy(values.begin(), values.end(), a.mutable_data());
  return std::move(a);
}

// A pose as a (7,) array [x, y, z, qw, qx, qy, qz].
py::array_t<double> pose_array(const Pose& p) {
  py::array_t<double> a(7);
  double* v = a.mutable_data();
  const double row[7] = {p.translation.x(), p.translation.y(), p.translation.z(), p.rotation.w(),
                         p.rotation.x(),    p.rotation.y(),    p.rotation.z()};
  std::copy(row, row + 7, v);
  return a;
}

// One pose from a (7,) array (or a 1 x 7 one), checked as query() checks its rows.
Pose one_pose(const Array& a) {
  const std::vector<Pose> poses = poses_from(a, false);
  if (poses.size() != 1) throw py::value_error("expected one pose, got " + std::to_string(poses.size()));
  return poses[0];
}

py::array_t<double> vector3(const Eigen::Vector3d& v) {
  py::array_t<double> a(3);
  std::copy(v.data(), v.data() + 3, a.mutable_data());
  return a;
}

Eigen::Vector3d vector3_from(const Array& a, const char* what) {
  if (a.ndim() != 1 || a.shape(0) != 3) throw py::value_error(std::string(what) + " must be a (3,) array");
  const Eigen::Vector3d v(a.data()[0], a.data()[1], a.data()[2]);
  if (!v.allFinite()) throw py::value_error(std::string(what) + " is not finite");
  return v;
}

py::dict strategy_dict(const StrategyAccuracy& s) {
  py::dict d;
  d["name"] = s.name;
  d["modes"] = s.modes;
  d["fits"] = s.fits;
  d["frame_ms_p50"] = s.frame_ms_p50, d["frame_ms_p99"] = s.frame_ms_p99;
  d["energy_error"] = s.energy_error, d["force_error"] = s.force_error, d["torque_error"] = s.torque_error;
  d["estimate_coverage"] = py::make_tuple(s.estimate_coverage[0], s.estimate_coverage[1], s.estimate_coverage[2]);
  d["estimate_ratio_median"] =
      py::make_tuple(s.estimate_ratio_median[0], s.estimate_ratio_median[1], s.estimate_ratio_median[2]);
  return d;
}

py::dict live_status_dict(const LiveStatus& s) {
  py::dict d;
  d["frames"] = s.frames, d["misses"] = s.misses, d["elapsed_s"] = s.elapsed_s;
  d["part_pose"] = pose_array(s.part);
  d["evaluated"] = s.evaluated, d["assembled"] = s.assembled;
  d["position_error"] = s.position_error, d["angle_error_deg"] = s.angle_error_deg;
  d["surface_deviation"] = s.surface_deviation;
  return d;
}

py::dict live_frame_dict(const LiveFrame& f) {
  py::dict d;
  d["time_s"] = f.time_s;
  d["device_pose"] = pose_array(f.device), d["part_pose"] = pose_array(f.part);
  d["energy"] = f.energy;
  d["force_sent"] = vector3(f.sent.force), d["torque_sent"] = vector3(f.sent.torque);
  d["contact_depth"] = f.contact_depth;
  d["modes"] = f.modes, d["frame_ms"] = f.frame_ms, d["missed"] = f.missed, d["flags"] = f.flags;
  return d;
}

// The module's exception: snapfit::Error as snapfit.Error.
void def_errors(py::module_& m) {
  static py::exception<Error> error(m, "Error", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const Error& e) {
      error(e.what());
    }
  });
}

// Scenes: reading them and their JSON text.
void def_scene(py::module_& m) {
  py::class_<Scene>(m, "Scene", "An assembly scene: two parts, the grid, the trajectory (docs/scenes.md).")
      .def_property_readonly("name", [](const Scene& s) { return s.name; })
      .def_property_readonly("units", [](const Scene& s) { return s.units; })
      .def("to_json", &scene_to_json, "The scene as JSON text (the scene file's schema).")
      .def("__repr__", [](const Scene& s) { return "<snapfit.Scene '" + s.name + "'>"; });

  m.def("load_scene", &load_scene, py::arg("path"),
        "Reads a scene file; raises snapfit.Error naming the file or field that is wrong.");
  m.def("_parse_scene", &parse_scene, py::arg("json_text"), py::arg("origin"));
}

// The per-frame engine: queries of poses and their timing.
void def_query_engine(py::module_& m) {
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
          "torque (N, 3), error_estimate (N, 3), flags (N,), modes (N,).")
      .def(
          "_time_batch",
          [](QueryEngine& q, const Array& poses, int repeats) {
            const std::vector<Pose> p = poses_from(poses, q.variant().translation_only);
            std::vector<QueryResult> results(p.size());
            std::vector<double> seconds;
            py::gil_scoped_release released;
            for (int r = 0; r < repeats; ++r) {
              const auto start = std::chrono::steady_clock::now();
              q.query_batch(p.data(), p.size(), results.data());
              seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
            }
            return seconds;
          },
          py::arg("poses"), py::arg("repeats"),
          "Seconds of each of `repeats` batches of the same poses timed in C++ around query_batch alone\n"
          "(perf/bench_python.py sets them beside query() called from Python).");
}

// An assembly on its device.
void def_assembly(py::module_& m) {
  py::class_<Assembly>(m, "Assembly", "A scene's parts, fields and spectra on one OpenCL device.")
      .def(py::init([](const Scene& scene, const std::string& device, bool use_cache, bool near_field) {
             AssemblyOptions o;
             o.device = device;
             o.use_cache = use_cache;
             o.near_field = near_field;
             py::gil_scoped_release released;
             return std::make_unique<Assembly>(scene, o);
           }),
           py::arg("scene"), py::arg("device") = "", py::arg("use_cache") = true, py::arg("near_field") = false,
           "Builds the parts, fields and spectra (cached). near_field: also the near-far strategy's near\n"
           "field (6-DOF scenes; seconds more), so that accuracy() measures it too.")
      .def_property_readonly("scene", &Assembly::scene, py::return_value_policy::reference_internal)
      .def_property_readonly("device_name", &Assembly::device_name)
      .def_property_readonly("spacing", &Assembly::spacing)
      .def_property_readonly("fft_dims", &Assembly::fft_dims)
      .def(
          "query_engine",
          [](const Assembly& a, const std::string& strategy) {
            const QueryVariant v = variant_named(a, strategy);
            py::gil_scoped_release released;
            return a.make_query_engine(v);
          },
          py::arg("strategy") = "tricubic",
          "A query engine for the scene's variant: 'tricubic' or 'trilinear' (the rotated spectrum\n"
          "interpolated), 'exact-product' (the product made exactly for each new rotation) or 'near-far'\n"
          "(its split into a smooth far sum and an exact near sum; needs Assembly(near_field=True)).");
}

// The pipeline's stages: a part's mesh and fields, m' tuned for a budget.
void def_stage_calls(py::module_& m) {
  m.def(
      "part_mesh",
      [](const Scene& scene, int part) {
        PartGeometry g;
        {
          py::gil_scoped_release released;
          g = part_geometry(scene, part);
        }
        py::array_t<double> vertices({static_cast<py::ssize_t>(g.vertices.size()), py::ssize_t(3)});
        py::array_t<std::int32_t> triangles({static_cast<py::ssize_t>(g.triangles.size()), py::ssize_t(3)});
        auto v = vertices.mutable_unchecked<2>();
        auto t = triangles.mutable_unchecked<2>();
        for (std::size_t i = 0; i < g.vertices.size(); ++i)
          for (int k = 0; k < 3; ++k) v(static_cast<py::ssize_t>(i), k) = g.vertices[i][k];
        for (std::size_t i = 0; i < g.triangles.size(); ++i)
          for (int k = 0; k < 3; ++k) t(static_cast<py::ssize_t>(i), k) = g.triangles[i][k];
        return py::make_tuple(vertices, triangles);
      },
      py::arg("scene"), py::arg("part"),
      "Part 1 or 2's mesh as the engine builds it (loaded, tessellated from STEP/IGES, or generated),\n"
      "in the part's own frame: (vertices (V, 3) float64, triangles (T, 3) int32).");

  m.def(
      "part_fields",
      [](const Scene& scene, int part, const std::string& device, bool use_cache) {
        PartFieldsRequest r;
        r.part = part, r.device = device, r.use_cache = use_cache;
        ScenePartFields f;
        {
          py::gil_scoped_release released;
          f = scene_part_fields(scene, r);
        }
        const DescriptorFields& d = f.result.fields;
        py::dict out;
        out["origin"] = py::make_tuple(d.grid.origin.x(), d.grid.origin.y(), d.grid.origin.z());
        out["spacing"] = d.grid.spacing;
        out["winding"] = grid_array(d.grid, d.winding);
        out["winding_bound"] = grid_array(d.grid, d.winding_bound);
        out["signed_distance"] = grid_array(d.grid, d.signed_distance);
        out["skeletal_density"] = grid_array(d.grid, d.skeletal_density);
        out["density_bound"] = grid_array(d.grid, d.density_bound);
        out["from_cache"] = f.result.from_cache;
        out["device"] = f.device;
        return out;
      },
      py::arg("scene"), py::arg("part"), py::arg("device") = "", py::arg("use_cache") = true,
      "Part 1 or 2's descriptor fields on its grid (from the field cache when present): arrays of shape\n"
      "(nz, ny, nx), point (i, j, k) at origin + spacing * (i, j, k) in the part's own frame; None where\n"
      "the scene's descriptor does not make that field.");

  m.def(
      "auto_tune",
      [](const Assembly& assembly, QueryEngine& engine, double margin, bool retune, std::size_t repetitions) {
        AutoTuneOptions o;
        o.margin = margin, o.retune = retune, o.repetitions = repetitions;
        TuningResult t;
        {
          py::gil_scoped_release released;
          t = auto_tune(assembly, engine, o);
        }
        return tuning_dict(t);
      },
      py::arg("assembly"), py::arg("engine"), py::arg("margin") = 0.25, py::arg("retune") = false,
      py::arg("repetitions") = 400,
      "m' for the scene's frame budget on this device (read from the tuning file when it matches),\n"
      "for the engine's variant; the engine keeps its m' (set engine.modes = result['chosen_modes']).\n"
      "Returns the sweep as arrays (modes, p50_ms, p99_ms, max_ms) and the choice.");
}

// Whole calls on an assembly: each strategy's accuracy, the rotation search.
void def_measurements(py::module_& m) {
  m.def(
      "accuracy",
      [](const Assembly& assembly, std::size_t poses, std::size_t repetitions, bool other_devices) {
        BudgetAccuracyRequest r;
        r.poses = poses, r.repetitions = repetitions, r.other_devices = other_devices;
        BudgetAccuracy a;
        {
          py::gil_scoped_release released;
          a = measure_budget_accuracy(assembly, r);
        }
        py::list strategies;
        for (const StrategyAccuracy& s : a.report.strategies) strategies.append(strategy_dict(s));
        py::dict d;
        d["strategies"] = strategies;
        d["best"] = a.report.best;
        d["why"] = a.report.why;
        d["reference_modes"] = a.report.reference_modes;
        d["device"] = a.device;
        d["strategy_file"] = a.strategy_file;
        return d;
      },
      py::arg("assembly"), py::arg("poses") = 24, py::arg("repetitions") = 400, py::arg("other_devices") = false,
      "`snapfit accuracy`: each query strategy's m' for the frame budget, its frame time, and its error\n"
      "against the exact reference at `poses` poses along the trajectory; 'best' indexes the lowest\n"
      "error that fits.");

  m.def(
      "search",
      [](const Scene& scene, std::optional<std::size_t> rotations, std::optional<double> step_deg, std::size_t top,
         const std::string& map_fft) {
        SearchRequest r;
        r.rotations = rotations, r.step_deg = step_deg, r.top = top, r.map_fft = map_fft;
        SearchResult found;
        {
          py::gil_scoped_release released;
          found = search(scene, r);
        }
        const py::ssize_t n = static_cast<py::ssize_t>(found.rotations.size());
        py::array_t<double> turns({n, py::ssize_t(4)});
        auto q = turns.mutable_unchecked<2>();
        for (py::ssize_t i = 0; i < n; ++i) {
          const Eigen::Quaterniond& x = found.rotations[static_cast<std::size_t>(i)];
          q(i, 0) = x.w(), q(i, 1) = x.x(), q(i, 2) = x.y(), q(i, 3) = x.z();
        }
        const py::ssize_t k = static_cast<py::ssize_t>(found.top.size());
        py::array_t<double> poses({k, py::ssize_t(7)}), refined({k, py::ssize_t(7)});
        py::array_t<double> energy(k), refined_energy(k);
        for (py::ssize_t i = 0; i < k; ++i) {
          const FoundPose& f = found.top[static_cast<std::size_t>(i)];
          const auto a = pose_array(f.pose), b = pose_array(f.refined.pose);
          std::copy(a.data(), a.data() + 7, poses.mutable_data() + 7 * i);
          std::copy(b.data(), b.data() + 7, refined.mutable_data() + 7 * i);
          energy.mutable_data()[i] = f.energy;
          refined_energy.mutable_data()[i] = f.refined.error.empty() ? f.refined.energy : std::nan("");
        }
        py::dict d;
        d["rotations"] = turns;
        d["best_energy"] = py::array_t<double>(n, found.best_energy.data());
        d["poses"] = poses, d["energy"] = energy;
        d["refined_poses"] = refined, d["refined_energy"] = refined_energy;
        d["map_fft"] = found.map_fft;
        return d;
      },
      py::arg("scene"), py::arg("rotations") = py::none(), py::arg("step_deg") = py::none(), py::arg("top") = 10,
      py::arg("map_fft") = "auto",
      "`snapfit search` on one process: an FFT map of the energy over all translations at each rotation\n"
      "of a grid (about `rotations` of them, or `step_deg` apart). Returns the grid (R, 4) quaternions\n"
      "w, x, y, z, the lowest energy of each map (R,), and the top poses (K, 7) with their energies,\n"
      "refined (NaN energy where a refinement failed).");
}

// Live sessions.
void def_live_session(py::module_& m) {
  py::class_<LiveSession>(m, "LiveSession",
                          "A live session: the haptic loop at the scene's rate on its own thread; a Python\n"
                          "program is the device (set_device_state or hold_device_pose) and reads the wrench\n"
                          "(latest).")
      .def(py::init([](const Scene& scene, const std::string& device, std::size_t modes, const std::string& strategy) {
             JobRequest r;
             r.device = device, r.modes = modes, r.strategy = strategy;
             py::gil_scoped_release released;
             return std::make_unique<LiveSession>(scene, r);
           }),
           py::arg("scene"), py::arg("device") = "", py::arg("modes") = 0, py::arg("strategy") = "auto")
      .def("start", &LiveSession::start, py::call_guard<py::gil_scoped_release>())
      .def(
          "stop",
          [](LiveSession& s) {
            LiveStatus status;
            {
              py::gil_scoped_release released;
              status = s.stop();
            }
            return live_status_dict(status);
          },
          "Ends the loop; returns its status (frames, misses, part 2's pose, the verdict).")
      .def(
          "set_device_state",
          [](LiveSession& s, const Array& pose, const Array& velocity, const Array& angular_velocity,
             std::uint32_t sequence) {
            BodyState state;
            state.pose = one_pose(pose);
            state.velocity = vector3_from(velocity, "velocity");
            state.angular_velocity = vector3_from(angular_velocity, "angular_velocity");
            s.set_device_state(state, sequence);
          },
          py::arg("pose"), py::arg("velocity"), py::arg("angular_velocity"), py::arg("sequence") = 0,
          "The device's state now: pose (7,), velocity and angular velocity (3,) in part 1's frame.\n"
          "Stream one a frame; when the next is late the pose is held and the wrench fades.")
      .def(
          "hold_device_pose", [](LiveSession& s, const Array& pose) { s.hold_device_pose(one_pose(pose)); },
          py::arg("pose"), "A pose (7,) that holds until the next one, never late (as a mouse).")
      .def("reset", &LiveSession::reset)
      .def(
          "latest", [](const LiveSession& s) { return live_frame_dict(s.latest()); },
          "The last frame: time, the device's and part 2's poses, energy, the wrench sent, m'.")
      .def(
          "status", [](const LiveSession& s) { return live_status_dict(s.status()); },
          "Frames, misses, part 2's pose and the verdict against the assembled pose, now.");
}

// `snapfit run`'s job.
void def_run_job(py::module_& m) {
  m.def(
      "run_job",
      [](const Scene& scene, const std::string& device, std::size_t modes, const std::string& strategy,
         bool simulated_time, bool retune, const std::string& out) {
        JobRequest r;
        r.device = device, r.modes = modes, r.strategy = strategy;
        r.simulated_time = simulated_time, r.retune = retune;
        JobResult j;
        RunReportFiles files;
        {
          py::gil_scoped_release released;
          const auto start = std::chrono::steady_clock::now();
          j = run_job(scene, r);
          if (!out.empty())
            files = write_job_report(out, j,
                                     std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        }
        py::dict d;
        d["report"] = out.empty() ? py::object(py::none()) : py::object(py::cast(files.written));
        d["device"] = j.device;
        d["loop_device"] = j.loop_device;
        d["strategy"] = j.strategy;
        d["strategy_chosen_by"] = j.strategy_chosen_by;
        d["tuning"] = tuning_dict(j.tuning);
        d["loop"] = j.loop ? py::object(loop_dict(*j.loop)) : py::object(py::none());
        d["evaluated"] = j.evaluated;
        d["assembled"] = j.assembled;
        d["final_position_error"] = j.final_position_error;
        d["final_angle_deg"] = j.final_angle_deg;
        d["final_surface_deviation"] = j.final_surface_deviation;
        return d;
      },
      py::arg("scene"), py::arg("device") = "", py::arg("modes") = 0, py::arg("strategy") = "auto",
      py::arg("simulated_time") = false, py::arg("retune") = false, py::arg("out") = "",
      "`snapfit run`'s job: the strategy and m' chosen for this device, the scripted assembly in the loop\n"
      "(its log as arrays under 'loop'), and the verdict; with `out`, the report folder `snapfit run`\n"
      "writes there (report.html, summary.json, ...), its files listed under 'report'.");
}

}  // namespace

PYBIND11_MODULE(_snapfit, m) {
  m.doc() = "snapfit: geometric energy, force and torque between two rigid parts (seed 000's method).";
  def_errors(m);
  def_scene(m);
  def_query_engine(m);
  def_assembly(m);
  def_stage_calls(m);
  def_measurements(m);
  def_live_session(m);
  def_run_job(m);
}
