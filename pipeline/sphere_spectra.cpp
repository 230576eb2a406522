#include "pipeline/sphere_spectra.h"

#include <chrono>
#include <cmath>
#include <sstream>

#include "engine/fields/ball_union_error.h"
#include "mesh/mesh_mass_properties.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

std::vector<Complex> times_i(const std::vector<float>& values) {
  std::vector<Complex> out(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) out[i] = Complex(0.0f, values[i]);
  return out;
}

}  // namespace

std::string spectrum_source_key(const PartDescriptorSpec& spec, double spacing) {
  if (spec.source == SpectrumSource::grid) return "grid";
  std::ostringstream key;
  key.precision(17);
  key << "spheres tolerance=" << spec.tolerance.value_or(spacing) << " protrusion=" << spec.protrusion
      << " method=" << spec.method << " nufft_tolerance=" << spec.nufft_tolerance;
  return key.str();
}

std::vector<float> ball_density_on_grid(const std::vector<Ball>& balls, double weight, const GridSpec& grid) {
  std::vector<float> density(grid.count(), 0.0f);
  for (const Ball& b : balls) {
    const Eigen::Vector3d lo = (b.centre.array() - b.radius - grid.origin.array()) / grid.spacing;
    const Eigen::Vector3d hi = (b.centre.array() + b.radius - grid.origin.array()) / grid.spacing;
    Eigen::Vector3i first, last;
    for (int a = 0; a < 3; ++a) {
      first[a] = std::max(0, static_cast<int>(std::ceil(lo[a])));
      last[a] = std::min(grid.dims[a] - 1, static_cast<int>(std::floor(hi[a])));
    }
    for (int k = first.z(); k <= last.z(); ++k)
      for (int j = first.y(); j <= last.y(); ++j)
        for (int i = first.x(); i <= last.x(); ++i)
          if ((grid.point(i, j, k) - b.centre).squaredNorm() <= b.radius * b.radius)
            density[grid.index(i, j, k)] += static_cast<float>(weight);
  }
  return density;
}

std::size_t nufft_from_balls(std::size_t modes) {
  // perf/bench_ndft_crossover (docs/spheres.md "The auto switch"): the NUFFT first won at 64
  // balls on 32^3 and 48^3 lattices (the direct sum at 32), at 256 on 64^3 (direct at 128), and
  // not yet at 128 on 96^3; each threshold is the geometric mean of the bracketing counts.
  return modes <= std::size_t(48 * 48 * 48) ? 45 : 181;
}

std::string ball_spectrum_method(const std::string& method, std::size_t balls, std::size_t modes) {
  if (method != "auto") return method;
  return balls < nufft_from_balls(modes) ? "direct" : "nufft";
}

PairSpectra compute_sphere_pair_spectra(const AssemblyPair& pair, const ComputeContext& ctx, const FftLibrary& fft,
                                        const SpectrumOptions& options, const DescriptorOptions& descriptors,
                                        const std::function<void(const std::string&)>& note) {
  struct PartBalls {
    bool spheres = false;
    std::vector<Ball> balls;
    double weight = 1;
    double decomposition_seconds = 0;
  };
  PartBalls parts[2];
  std::vector<Complex> samples[2];
  for (int p = 1; p <= 2; ++p) {
    const PartSpec& spec = p == 1 ? pair.scene.part1 : pair.scene.part2;
    PartBalls& out = parts[p - 1];
    out.spheres = spec.descriptor.source == SpectrumSource::spheres;
    if (!out.spheres) {
      samples[p - 1] = times_i(affinity_imaginary(pair.fields(p).fields));
      continue;
    }
    SphereDecompositionParams params;
    params.tolerance = spec.descriptor.tolerance.value_or(pair.grids.spacing);
    params.protrusion = spec.descriptor.protrusion;
    const Mesh& mesh = pair.part(p).mesh;
    const SphereDecomposition d = decompose_part(ctx, mesh, pair.scene.descriptor, params, descriptors);
    out.balls = d.balls;
    out.decomposition_seconds = d.seconds;
    double ball_volume = 0;
    for (const Ball& b : d.balls) ball_volume += ball_transform(b.radius, 0);
    out.weight = std::abs(solid_moments(mesh).volume) / ball_volume;
    samples[p - 1] = times_i(ball_density_on_grid(out.balls, out.weight, pair.grid(p)));
  }
  PairSpectra spectra = compute_pair_spectra(fft, ctx, pair.grid(1), samples[0], pair.grid(2), samples[1], options);
  for (int p = 1; p <= 2; ++p) {
    const PartBalls& in = parts[p - 1];
    if (!in.spheres) continue;
    const PartDescriptorSpec& spec = (p == 1 ? pair.scene.part1 : pair.scene.part2).descriptor;
    PartSpectrum& part = p == 1 ? spectra.part1 : spectra.part2;
    const auto start = std::chrono::steady_clock::now();
    FrequencyLattice lattice;
    lattice.dims = spectra.dims;
    lattice.length = spectra.length;
    lattice.centre = part.centre;
    const std::string method = ball_spectrum_method(spec.method, in.balls.size(), lattice.count());
    std::vector<std::complex<float>> values;
    if (method == "direct") {
      values = ball_spectrum_direct(ctx, in.balls, lattice, {}, descriptors.program_cache);
    } else {
      BallNufftOptions nufft;
      nufft.tolerance = spec.nufft_tolerance;
      values = ball_spectrum_nufft(fft, ctx, in.balls, lattice, nufft);
    }
    for (std::size_t k = 0; k < values.size(); ++k)
      part.rho[k] = Complex(0.0f, static_cast<float>(in.weight)) * values[k];
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::ostringstream line;
    line.precision(3);
    line << "part " << p << ": spectrum from " << in.balls.size() << " balls (" << method << " NDFT onto "
         << lattice.count() << " modes) in " << in.decomposition_seconds << " s + " << seconds << " s";
    if (note) note(line.str());
  }
  return spectra;
}

}  // namespace snapfit
