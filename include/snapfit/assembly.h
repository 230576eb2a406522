#pragma once
// An assembly: the two parts of a scene on one OpenCL device, with everything the
// per-frame queries need precomputed (Behandish & Ilies 2016 sections 3.1-3.2): both parts built and
// validated, their descriptor fields on a common grid, and their Fourier spectra, each
// from the on-disk caches when a matching entry exists. From it come query engines
// (include/snapfit/query.h), the tuned m' (tuning.h) and the haptic loop's
// configuration (haptic_loop.h).
//
//   snapfit::Assembly assembly(snapfit::load_scene("scenes/default.json"));
//   std::unique_ptr<snapfit::QueryEngine> engine = assembly.make_query_engine();
//   engine->set_modes(4096);
//   snapfit::QueryResult r = engine->query(pose);  // energy, force, torque of part 2 at pose
#include <array>
#include <cstddef>
#include <functional>
#include <memory>
#include <string>

#include "snapfit/query.h"
#include "snapfit/scene.h"

namespace snapfit {

struct AssemblyOptions {
  // The OpenCL device: an index, "platform:device", cpu|gpu|accelerator, or a name
  // substring (as `snapfit devices` lists them); "" takes $SNAPFIT_DEVICE, else PoCL's
  // CPU device.
  std::string device;
  bool use_cache = true;      // field, spectra and program caches (under $SNAPFIT_CACHE_DIR)
  double oversampling = 2.0;  // zero padding in space, so the spectra interpolate at rotated frequencies
  bool progress = false;      // progress bars on stderr while fields are computed
  // Also the near field of the near-far strategy (QueryVariant::near_far) for a 6-DOF
  // scene: seconds and tens of MB more, so only where that strategy may run.
  bool near_field = false;
  std::function<void(const std::string&)> note;  // cache and device messages; default: stderr
};

class Assembly {
 public:
  // Builds everything (minutes for a large part on a CPU the first time; the caches make
  // later builds fast). Throws snapfit::Error naming the part, file, field or device
  // that failed.
  explicit Assembly(const Scene& scene, const AssemblyOptions& options = {});
  ~Assembly();
  Assembly(Assembly&&) noexcept;
  Assembly& operator=(Assembly&&) noexcept;

  const Scene& scene() const;
  std::string device_name() const;
  double spacing() const;                       // the grids' spacing, scene units
  std::array<std::size_t, 3> fft_dims() const;  // the common frequency grid

  // The variant the scene needs (its motion and outputs) with the given interpolation.
  QueryVariant query_variant(Interpolation interpolation = Interpolation::tricubic) const;
  // A query engine on the assembly's device; it may outlive the assembly.
  std::unique_ptr<QueryEngine> make_query_engine(const QueryVariant& variant) const;
  std::unique_ptr<QueryEngine> make_query_engine() const { return make_query_engine(query_variant()); }

 private:
  friend struct AssemblyAccess;  // the library's own stages reach the device and the spectra through it
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace snapfit
