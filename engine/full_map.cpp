#include "engine/full_map.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "engine/kernel_sources.h"
#include "snapfit/error.h"

namespace snapfit {

TranslationMap translational_energy_map(const FftLibrary& library, const ComputeContext& ctx,
                                        const PairSpectra& spectra, const Eigen::Matrix3d& R,
                                        Interpolation interpolation, std::size_t modes,
                                        const ProgramCacheConfig& cache) {
  const auto start = std::chrono::steady_clock::now();
  const auto& dims = spectra.dims;
  const std::size_t total = dims[0] * dims[1] * dims[2];
  // Low-pass radius: the |w| of the modes-th smallest node.
  float max_w2 = std::numeric_limits<float>::infinity();
  if (modes > 0 && modes < total) {
    std::vector<float> w2(total);
    for (std::size_t z = 0; z < dims[2]; ++z)
      for (std::size_t y = 0; y < dims[1]; ++y)
        for (std::size_t x = 0; x < dims[0]; ++x)
          w2[x + dims[0] * (y + dims[1] * z)] =
              float(std::pow(spectra.frequency(0, x), 2) + std::pow(spectra.frequency(1, y), 2) +
                    std::pow(spectra.frequency(2, z), 2));
    std::nth_element(w2.begin(), w2.begin() + (modes - 1), w2.end());
    max_w2 = w2[modes - 1];
  }
  const Eigen::Vector3d shift = R * spectra.part2.centre - spectra.part1.centre;
  TranslationMap map;
  std::vector<std::complex<float>> f(total);
  try {
    const std::string options =
        std::string("-cl-std=CL1.2") + (interpolation == Interpolation::tricubic ? " -D TRICUBIC" : "");
    cl::Kernel kernel(
        build_program(ctx, "full_map", kernel_source("spectrum_sample") + kernel_source("full_map"), options, cache)
            .program,
        "spectrum_product");
    auto upload = [&](const std::vector<Complex>& v) {
      return cl::Buffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(Complex) * v.size(),
                        const_cast<Complex*>(v.data()));
    };
    cl::Buffer s1 = upload(spectra.part1.rho), s2 = upload(spectra.part2.rho);
    cl::Buffer product(ctx.context, CL_MEM_READ_WRITE, sizeof(Complex) * total);
    cl::Buffer result(ctx.context, CL_MEM_READ_WRITE, sizeof(Complex) * total);
    cl_float16 pose{};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) pose.s[3 * r + c] = static_cast<float>(R(r, c));
    for (int a = 0; a < 3; ++a) pose.s[9 + a] = static_cast<float>(shift[a]);
    kernel.setArg(0, s1);
    kernel.setArg(1, s2);
    kernel.setArg(2, cl_int4{{int(dims[0]), int(dims[1]), int(dims[2]), 0}});
    kernel.setArg(3,
                  cl_float4{{float(spectra.length.x()), float(spectra.length.y()), float(spectra.length.z()), 0.0f}});
    kernel.setArg(4, pose);
    kernel.setArg(5, static_cast<float>(1.0 / (spectra.length.x() * spectra.length.y() * spectra.length.z())));
    kernel.setArg(6, max_w2);
    kernel.setArg(7, product);
    ctx.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(total));
    const Fft3d fft(library, ctx, dims);
    fft.transform(FftDirection::inverse, product, result);  // f(t_j) = sum_k P_k e^{2 pi i k.j / N}
    ctx.queue.enqueueReadBuffer(result, CL_TRUE, 0, sizeof(Complex) * total, f.data());
  } catch (const cl::Error& e) {
    throw Error("full map failed on " + ctx.device.info.name + ": " + e.what() + " (error " + std::to_string(e.err()) +
                ")");
  }
  // Regular order: translation index j' from -floor(N/2) to N - 1 - floor(N/2) per axis.
  map.grid.spacing = spectra.spacing;
  map.grid.dims = Eigen::Vector3i(int(dims[0]), int(dims[1]), int(dims[2]));
  for (int a = 0; a < 3; ++a) map.grid.origin[a] = -spectra.spacing * double(dims[a] / 2);
  map.energy.assign(total, std::numeric_limits<float>::quiet_NaN());
  const Eigen::Vector3d reach = spectra.part1.half_extent + R.cwiseAbs() * spectra.part2.half_extent;
  for (std::size_t z = 0; z < dims[2]; ++z)
    for (std::size_t y = 0; y < dims[1]; ++y)
      for (std::size_t x = 0; x < dims[0]; ++x) {
        const Eigen::Vector3d t = map.grid.point(int(x), int(y), int(z));
        // FFT index of translation t: j = j' mod N.
        std::size_t j[3];
        for (int a = 0; a < 3; ++a) {
          const long jp = std::lround(t[a] / spectra.spacing);
          j[a] = static_cast<std::size_t>((jp % long(dims[a]) + long(dims[a])) % long(dims[a]));
        }
        // Same aliasing rule as the pose queries (engine/pose_query.cpp).
        if ((((t + shift).cwiseAbs() + reach).array() > spectra.length.array()).any()) continue;
        map.energy[map.grid.index(int(x), int(y), int(z))] = -f[j[0] + dims[0] * (j[1] + dims[1] * j[2])].real();
      }
  map.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return map;
}

}  // namespace snapfit
