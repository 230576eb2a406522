// clFFT (what snapfit uses, engine/spectra/fft3d.h; unmaintained since 2017) against FFTW and
// VkFFT on the same 3D transforms, side by side in one run, and the full-map throughput
// (rotations per second) with each library's inverse FFT.
//
//   bench_fft --help lists its options.
//
// Libraries (all single precision, complex-to-complex, interleaved, x fastest):
//   clfft   engine/spectra/fft3d.h Fft3d on the OpenCL device (out of place, inverse unnormalized)
//   vkfft   VkFFT (Debian libvkfft-dev, header-only, VKFFT_BACKEND=3: OpenCL) on the same
//           device and queue; out of place (isInputFormatted + inverseReturnToInputBuffer:
//           forward input -> buffer, inverse buffer -> input); inverse unnormalized
//   fftw    FFTW 3 fftwf on the host, its own planner (FFTW_MEASURE), threads = cores
//           (fftw3f_threads); out of place, inverse (FFTW_BACKWARD) unnormalized
// Reference: FFTW in double precision (fftw_plan_dft_3d, FFTW_ESTIMATE) of the same input.
//
// 1. transforms  sizes 64^3, 128^3 and the FFT grid snapfit's default scene uses
//                (scenes/default.json: the parts' descriptor grids, oversampling 2, each axis
//                rounded up by next_fft_size, as engine/spectra/spectra.cpp does); per library and
//                direction: plan time (clFFT: Fft3d constructor = create + bake; VkFFT:
//                initializeVkFFT, which generates and compiles its kernels; FFTW: planning
//                both directions with FFTW_MEASURE), then N timed transforms (default 30,
//                --quick 5) after 2 warm-up ones, wall clock around one transform including
//                the wait for the device (clFinish); p50 and min; GFLOP/s = 5 n log2(n) / t
//                with n the number of points. Input: seeded uniform random complex values in
//                [-1, 1]^2. VkFFT overwrites its input buffer in both directions, so each of
//                its transforms gets a fresh copy of the input first (a device copy outside
//                the timed interval); clFFT and FFTW (out of place) keep their input.
//                Agreement: max over points of |X - X_ref| / max over points of |X_ref|, per
//                library and direction, against the double-precision FFTW transform.
// 2. full maps   one rotation = snapfit's spectrum_product kernel (kernels/full_map.cl, the
//                pointwise product with the rotated, trilinearly interpolated spectrum of
//                part 2) + one inverse 3D FFT, at 64^3 and 128^3 (and the scene's grid);
//                spectra of two synthetic parts (a ball and a box, indicator-like fields,
//                computed with compute_pair_spectra). Per library: rotations per second from
//                the median of M timed rotations (default 20, --quick 3), each with a
//                different seeded random rotation; the product kernel runs on the device for
//                all three; FFTW also needs the product read back to the host (timed in its
//                rotation); the three take turns rotation by rotation (interleaved), so
//                that load from other processes weighs on all alike. Also the real code
//                path, engine/maps/full_map.h translational_energy_map (all modes): cold (first
//                call) and warm; it uploads both spectra, bakes a clFFT plan, runs product + inverse FFT, reads
//                back and re-orders the map on the host, every call. Agreement: the maps of
//                each library for one rotation against FFTW double of the same product.
// Contention: each row records the load average and the cores other processes kept busy
// meanwhile (/proc/stat); a row during which they used more than 0.25 cores is measured
// again after 15 s, up to 2 times (240 s of waiting per run at most), keeping the quietest
// attempt (not in --quick).
// Output in DIR (default results/bench_fft): fft.csv, maps.csv, fft.json and charts.html
// (time, throughput and maps per second against size); a table on stdout and a one-line verdict (the
// fastest library per size and direction, and per map size), computed from the figures.
#include <CL/opencl.hpp>
#include <fftw3.h>

#ifndef VKFFT_BACKEND
#error "bench_fft needs VKFFT_BACKEND=3 (VkFFT's OpenCL backend); perf/CMakeLists.txt defines it"
#endif
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wall"
#pragma GCC diagnostic ignored "-Wextra"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wunused-variable"
#pragma GCC diagnostic ignored "-Wunused-but-set-variable"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wdeprecated-declarations"
#include <vkFFT.h>
#pragma GCC diagnostic pop

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "engine/maps/full_map.h"
#include "engine/runtime/compute_context.h"
#include "engine/runtime/device.h"
#include "engine/runtime/kernel_sources.h"
#include "engine/runtime/program_cache.h"
#include "engine/spectra/fft3d.h"
#include "engine/spectra/spectra.h"
#include "perf/bench_common.h"
#include "perf/bench_options.h"
#include "perf/bench_spectra.h"
#include "perf/quiet_guard.h"
#include "pipeline/assembly_pair.h"
#include "snapfit/error.h"
#include "snapfit/scene.h"

namespace {

using namespace snapfit::bench;  // perf/*.h: tables, medians, contention, CSV, spectra

using Clock = std::chrono::steady_clock;
using Dims = std::array<std::size_t, 3>;
using cf = std::complex<float>;
using cd = std::complex<double>;

// ---------------------------------------------------------------- command line

struct Args : CommonArgs {
  int repeats = 0;  // 0: 30, or 5 with --quick
};

Args parse_args(int argc, char** argv) {
  Args a;
  a.out = "results/bench_fft";
  a.command_line = command_line(argc, argv);
  CLI::App app{
      "clFFT against FFTW and VkFFT on the same 3D transforms, and the full-map throughput with each library's "
      "inverse FFT",
      "bench_fft"};
  add_common_options(app, a.quick, a.device, a.out,
                     "64^3 and 128^3 only, 5 transforms and 3 map rotations per point (under a minute)");
  app.add_option("--repeats", a.repeats, "timed transforms per point (0: 30, --quick 5)")->check(CLI::Range(1, 100000));
  parse(app, argc, argv);
  return a;
}

// ---------------------------------------------------------------- small helpers

double minimum(const std::vector<double>& v) {
  return v.empty() ? std::numeric_limits<double>::quiet_NaN() : *std::min_element(v.begin(), v.end());
}

std::string dims_text(const Dims& d) {
  return std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]);
}
std::size_t count_of(const Dims& d) { return d[0] * d[1] * d[2]; }
double flops_of(const Dims& d) {
  const double n = double(count_of(d));
  return 5.0 * n * std::log2(n);
}

// max_i |x_i - ref_i| / max_i |ref_i|
double max_rel_diff(const std::vector<cf>& x, const std::vector<cd>& ref) {
  double diff = 0, scale = 0;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    diff = std::max(diff, std::abs(cd(x[i]) - ref[i]));
    scale = std::max(scale, std::abs(ref[i]));
  }
  return scale > 0 ? diff / scale : std::numeric_limits<double>::quiet_NaN();
}

void cl_check(cl_int e, const std::string& what) {
  if (e != CL_SUCCESS) throw snapfit::Error(what + " (OpenCL error " + std::to_string(e) + ")");
}

// ---------------------------------------------------------------- the three libraries

// FFTW float plans (both directions) on host arrays, out of place.
struct FftwPlans {
  Dims dims;
  fftwf_complex* in = nullptr;
  fftwf_complex* out = nullptr;
  fftwf_plan forward = nullptr, inverse = nullptr;
  double plan_s = 0;
  FftwPlans(const Dims& d, unsigned flags) : dims(d) {
    const std::size_t n = count_of(d);
    in = fftwf_alloc_complex(n);
    out = fftwf_alloc_complex(n);
    if (!in || !out) throw snapfit::Error("FFTW: cannot allocate " + dims_text(d));
    const auto t0 = Clock::now();
    // FFTW is row-major (last index fastest): x fastest means (nz, ny, nx).
    forward = fftwf_plan_dft_3d(int(d[2]), int(d[1]), int(d[0]), in, out, FFTW_FORWARD, flags);
    inverse = fftwf_plan_dft_3d(int(d[2]), int(d[1]), int(d[0]), in, out, FFTW_BACKWARD, flags);
    plan_s = seconds_since(t0);
    if (!forward || !inverse) throw snapfit::Error("FFTW: cannot plan " + dims_text(d));
  }
  ~FftwPlans() {
    if (forward) fftwf_destroy_plan(forward);
    if (inverse) fftwf_destroy_plan(inverse);
    fftwf_free(in);
    fftwf_free(out);
  }
  FftwPlans(const FftwPlans&) = delete;
  FftwPlans& operator=(const FftwPlans&) = delete;
  void set_input(const std::vector<cf>& x) {
    std::memcpy(in, static_cast<const void*>(x.data()), sizeof(cf) * x.size());
  }
  std::vector<cf> output() const {
    std::vector<cf> o(count_of(dims));
    std::memcpy(static_cast<void*>(o.data()), out, sizeof(cf) * o.size());
    return o;
  }
};

// Double-precision FFTW reference of x (forward or unnormalized backward).
std::vector<cd> reference_fft(const Dims& d, const std::vector<cf>& x, int sign) {
  const std::size_t n = count_of(d);
  fftw_complex* in = fftw_alloc_complex(n);
  fftw_complex* out = fftw_alloc_complex(n);
  fftw_plan p = fftw_plan_dft_3d(int(d[2]), int(d[1]), int(d[0]), in, out, sign, FFTW_ESTIMATE);
  if (!in || !out || !p) throw snapfit::Error("FFTW double: cannot plan " + dims_text(d));
  for (std::size_t i = 0; i < n; ++i) in[i][0] = x[i].real(), in[i][1] = x[i].imag();
  fftw_execute(p);
  std::vector<cd> r(n);
  for (std::size_t i = 0; i < n; ++i) r[i] = cd(out[i][0], out[i][1]);
  fftw_destroy_plan(p);
  fftw_free(in);
  fftw_free(out);
  return r;
}

// A VkFFT application on the snapfit device: `input` -> `buffer` forward, `buffer` ->
// `input` inverse (out of place both ways), unnormalized. Both buffers are overwritten.
struct VkfftPlan {
  VkFFTApplication app{};
  cl_device_id device;
  cl_context context;
  cl_command_queue queue;
  cl_mem input, buffer;
  std::uint64_t bytes = 0;
  double plan_s = 0;
  bool ok = false;
  VkfftPlan(const snapfit::ComputeContext& ctx, const Dims& d, const cl::Buffer& in, const cl::Buffer& buf)
      : device(ctx.device.device()), context(ctx.context()), queue(ctx.queue()), input(in()), buffer(buf()) {
    VkFFTConfiguration c{};
    c.FFTdim = 3;
    c.size[0] = d[0];
    c.size[1] = d[1];
    c.size[2] = d[2];
    c.device = &device;
    c.context = &context;
    c.commandQueue = &queue;
    bytes = sizeof(cf) * count_of(d);
    c.bufferSize = &bytes;
    c.inputBufferSize = &bytes;
    c.buffer = &buffer;
    c.inputBuffer = &input;
    c.isInputFormatted = 1;
    c.inverseReturnToInputBuffer = 1;
    c.normalize = 0;
    const auto t0 = Clock::now();
    const VkFFTResult r = initializeVkFFT(&app, c);
    plan_s = seconds_since(t0);
    if (r != VKFFT_SUCCESS)
      throw snapfit::Error("VkFFT: initializeVkFFT failed for " + dims_text(d) + " on " + ctx.device.info.name +
                           " (VkFFTResult " + std::to_string(int(r)) + ")");
    ok = true;
  }
  ~VkfftPlan() {
    if (ok) deleteVkFFT(&app);
  }
  VkfftPlan(const VkfftPlan&) = delete;
  VkfftPlan& operator=(const VkfftPlan&) = delete;
  // inverse: 0 forward (input -> buffer), 1 inverse (buffer -> input); blocks until done.
  void run(int inverse) {
    VkFFTLaunchParams lp{};
    lp.commandQueue = &queue;
    lp.buffer = &buffer;
    lp.inputBuffer = &input;
    const VkFFTResult r = VkFFTAppend(&app, inverse ? 1 : -1, &lp);
    if (r != VKFFT_SUCCESS)
      throw snapfit::Error("VkFFT: VkFFTAppend failed (VkFFTResult " + std::to_string(int(r)) + ")");
    cl_check(clFinish(queue), "VkFFT: clFinish");
  }
};

// ---------------------------------------------------------------- 1. transforms

// Rows are re-measured while other processes keep cores busy (perf/quiet_guard.h); off
// in --quick.
QuietGuard g_quiet{true, 0.25, 2, 15, 240};

// Runs `body` (which fills row.times_s / total_s ...) under the guard, with the load
// around it; the row keeps the quietest attempt, its number and its contention.
template <class Row, class F>
void quiet_measure(Row& row, const std::string& what, F&& body) {
  int attempt = 0, attempts = 0;
  double others = 0;
  const auto measure = [&] {
    Row r = row;
    r.attempts = ++attempt;
    r.load_before = load1();
    body(r);
    r.load_after = load1();
    return r;
  };
  row = g_quiet.run(what, measure, others, attempts);
  row.other_cores = others;
}

struct TransformRow {
  std::string library, direction;  // direction: forward | inverse
  Dims dims{};
  double plan_s = 0;  // plan for both directions (one plan object per library)
  std::vector<double> times_s;
  double p50_s = 0, min_s = 0, gflops_p50 = 0, gflops_min = 0;
  double max_rel_diff = 0;  // against FFTW double
  double load_before = 0, load_after = 0;
  double other_cores = 0;  // cores other processes kept busy while this row was timed
  int attempts = 1;
};

void finish_row(TransformRow& r) {
  r.p50_s = median(r.times_s);
  r.min_s = minimum(r.times_s);
  r.gflops_p50 = flops_of(r.dims) / r.p50_s * 1e-9;
  r.gflops_min = flops_of(r.dims) / r.min_s * 1e-9;
}

std::vector<TransformRow> bench_transforms(const snapfit::FftLibrary& lib, const snapfit::ComputeContext& ctx,
                                           const Dims& d, int warmup, int repeats, unsigned seed) {
  const std::size_t n = count_of(d);
  std::vector<cf> x(n);
  {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (auto& v : x) v = cf(u(rng), u(rng));
  }
  const std::vector<cd> ref_fwd = reference_fft(d, x, FFTW_FORWARD);
  const std::vector<cd> ref_inv = reference_fft(d, x, FFTW_BACKWARD);
  const std::vector<cd>* refs[2] = {&ref_fwd, &ref_inv};
  std::vector<TransformRow> rows;
  const std::size_t bytes = sizeof(cf) * n;
  // A row per direction k: `transform(k)` runs one transform and returns its seconds,
  // `output(k)` reads its result.
  auto measure_both = [&](const std::string& library, double plan_s, auto&& transform, auto&& output) {
    for (int k = 0; k < 2; ++k) {
      TransformRow r;
      r.library = library;
      r.direction = k == 0 ? "forward" : "inverse";
      r.dims = d;
      r.plan_s = plan_s;
      quiet_measure(r, library + " " + dims_text(d), [&](TransformRow& q) {
        for (int i = 0; i < warmup; ++i) transform(k);
        for (int i = 0; i < repeats; ++i) q.times_s.push_back(transform(k));
      });
      r.max_rel_diff = max_rel_diff(output(k), *refs[k]);
      finish_row(r);
      rows.push_back(r);
    }
  };
  auto read = [&](const cl::Buffer& b) {
    std::vector<cf> y(n);
    ctx.queue.enqueueReadBuffer(b, CL_TRUE, 0, bytes, y.data());
    return y;
  };
  {  // clFFT
    const auto t0 = Clock::now();
    const snapfit::Fft3d fft(lib, ctx, d);
    const double plan_s = seconds_since(t0);
    cl::Buffer in(ctx.context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, bytes, x.data());
    cl::Buffer out(ctx.context, CL_MEM_READ_WRITE, bytes);
    measure_both(
        "clfft", plan_s,
        [&](int k) {
          const auto t = Clock::now();
          fft.transform(k == 0 ? snapfit::FftDirection::forward : snapfit::FftDirection::inverse, in, out);
          return seconds_since(t);
        },
        [&](int) { return read(out); });
  }
  {  // VkFFT overwrites its input: each transform reads a fresh copy, made untimed
    cl::Buffer pristine(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes, x.data());
    cl::Buffer input(ctx.context, CL_MEM_READ_WRITE, bytes), buffer(ctx.context, CL_MEM_READ_WRITE, bytes);
    VkfftPlan plan(ctx, d, input, buffer);
    measure_both(
        "vkfft", plan.plan_s,
        [&](int k) {
          ctx.queue.enqueueCopyBuffer(pristine, k == 0 ? input : buffer, 0, 0, bytes);
          ctx.queue.finish();
          const auto t = Clock::now();
          plan.run(k);
          return seconds_since(t);
        },
        [&](int k) { return read(k == 0 ? buffer : input); });
  }
  // FFTW (planning with FFTW_MEASURE overwrites the arrays: the input is set afterwards)
  {
    FftwPlans plans(d, FFTW_MEASURE);
    plans.set_input(x);
    measure_both(
        "fftw", plans.plan_s,
        [&](int k) {
          const auto t = Clock::now();
          fftwf_execute(k == 0 ? plans.forward : plans.inverse);
          return seconds_since(t);
        },
        [&](int) { return plans.output(); });
  }
  return rows;
}

// ---------------------------------------------------------------- 2. full maps

struct MapRow {
  std::string library;  // clfft | vkfft | fftw | full_map (the real path)
  Dims dims{};
  std::vector<double> total_s, product_s, readback_s, fft_s;
  double plan_s = 0;
  double cold_s = std::numeric_limits<double>::quiet_NaN();  // full_map only
  double rotations_per_s = 0, median_s = 0, product_median_s = 0, readback_median_s = 0, fft_median_s = 0;
  double max_rel_diff = std::numeric_limits<double>::quiet_NaN();  // against FFTW double of the same product
  double load_before = 0, load_after = 0;
  double other_cores = 0;
  int attempts = 1;
};

// `count` rotations, uniform (normalised Gaussian quaternions), from `seed`.
std::vector<Eigen::Matrix3d> random_rotations(int count, unsigned seed) {
  std::vector<Eigen::Matrix3d> rots;
  std::mt19937 rng(seed);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int i = 0; i < count; ++i) {
    Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
    rots.push_back(q.normalized().toRotationMatrix());
  }
  return rots;
}

// The real code path (engine/maps/full_map.cpp), trilinear as in seed 000: the first map cold,
// then `warm_real` warm ones.
MapRow measure_full_map(const snapfit::FftLibrary& lib, const snapfit::ComputeContext& ctx,
                        const snapfit::PairSpectra& s, const Dims& d, const std::vector<Eigen::Matrix3d>& rots,
                        int warm_real) {
  MapRow r;
  r.library = "full_map";
  r.dims = d;
  double cold = std::numeric_limits<double>::quiet_NaN();
  quiet_measure(r, "full_map " + dims_text(d), [&](MapRow& q) {
    std::size_t i = 0;
    q.total_s = time_full_maps(lib, ctx, s, snapfit::Interpolation::trilinear, warm_real, cold,
                               [&] { return rots[i++ % rots.size()]; });
  });
  r.cold_s = cold;
  r.median_s = median(r.total_s);
  r.rotations_per_s = 1.0 / r.median_s;
  return r;
}

std::vector<MapRow> bench_maps(const snapfit::FftLibrary& lib, const snapfit::ComputeContext& ctx, const Dims& d,
                               int rotations, int warm_real, unsigned seed) {
  const double spacing = 0.6;
  const snapfit::PairSpectra s = synthetic_spectra(lib, ctx, d, spacing);
  const std::size_t n = count_of(d), bytes = sizeof(cf) * n;
  const std::vector<Eigen::Matrix3d> rots = random_rotations(rotations + 2, seed);
  std::vector<MapRow> rows = {measure_full_map(lib, ctx, s, d, rots, warm_real)};

  // Product kernel + each library's inverse FFT.
  cl::Kernel kernel(snapfit::build_program(
                        ctx, "full_map", snapfit::kernel_source("spectrum_sample") + snapfit::kernel_source("full_map"),
                        "-cl-std=CL1.2")
                        .program,
                    "spectrum_product");
  cl::Buffer s1(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes, const_cast<cf*>(s.part1.rho.data()));
  cl::Buffer s2(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes, const_cast<cf*>(s.part2.rho.data()));
  cl::Buffer product(ctx.context, CL_MEM_READ_WRITE, bytes), result(ctx.context, CL_MEM_READ_WRITE, bytes);
  cl::Buffer poses(ctx.context, CL_MEM_READ_ONLY, sizeof(cl_float16));  // a batch of one rotation
  set_args(kernel, s1, s2, cl_int4{{int(d[0]), int(d[1]), int(d[2]), 0}},
           cl_float4{{float(s.length.x()), float(s.length.y()), float(s.length.z()), 0.0f}}, poses,
           static_cast<float>(1.0 / (s.length.x() * s.length.y() * s.length.z())),
           std::numeric_limits<float>::infinity(), product);
  auto run_product = [&](const Eigen::Matrix3d& R) {
    const Eigen::Vector3d shift = R * s.part2.centre - s.part1.centre;
    cl_float16 pose{};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) pose.s[3 * a + b] = static_cast<float>(R(a, b));
    for (int a = 0; a < 3; ++a) pose.s[9 + a] = static_cast<float>(shift[a]);
    ctx.queue.enqueueWriteBuffer(poses, CL_TRUE, 0, sizeof pose, &pose);
    ctx.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(n, 1));
    ctx.queue.finish();
  };
  // Reference map for the check rotation: FFTW double of the product the kernel made.
  const Eigen::Matrix3d& R_check = rots.back();
  run_product(R_check);
  std::vector<cf> prod_check(n);
  ctx.queue.enqueueReadBuffer(product, CL_TRUE, 0, bytes, prod_check.data());
  const std::vector<cd> ref = reference_fft(d, prod_check, FFTW_BACKWARD);

  const auto t_clfft = Clock::now();
  const snapfit::Fft3d clfft(lib, ctx, d);
  const double clfft_plan_s = seconds_since(t_clfft);
  cl::Buffer vk_in(ctx.context, CL_MEM_READ_WRITE, bytes);
  VkfftPlan vk(ctx, d, result, product);  // inverse: product -> result
  FftwPlans fw(d, FFTW_MEASURE);
  // The three libraries take turns rotation by rotation, so that other processes on this
  // shared machine weigh on all three alike.
  const std::vector<std::string> names = {"clfft", "vkfft", "fftw"};
  std::vector<MapRow> lib_rows(names.size());
  auto rotation = [&](std::size_t k, const Eigen::Matrix3d& R, bool timed) {
    const std::string& name = names[k];
    MapRow& r = lib_rows[k];
    const auto t0 = Clock::now();
    run_product(R);
    const auto t1 = Clock::now();
    auto t2 = t1;
    if (name == "clfft") {
      clfft.transform(snapfit::FftDirection::inverse, product, result);
    } else if (name == "vkfft") {
      vk.run(1);
    } else {
      ctx.queue.enqueueReadBuffer(product, CL_TRUE, 0, bytes, fw.in);
      t2 = Clock::now();
      fftwf_execute(fw.inverse);
    }
    const auto t3 = Clock::now();
    if (!timed) return;
    r.product_s.push_back(std::chrono::duration<double>(t1 - t0).count());
    r.readback_s.push_back(std::chrono::duration<double>(t2 - t1).count());
    r.fft_s.push_back(std::chrono::duration<double>(t3 - t2).count());
    r.total_s.push_back(std::chrono::duration<double>(t3 - t0).count());
  };
  for (std::size_t k = 0; k < names.size(); ++k) {
    MapRow& r = lib_rows[k];
    r.library = names[k];
    r.dims = d;
    r.plan_s = names[k] == "clfft" ? clfft_plan_s : names[k] == "vkfft" ? vk.plan_s : fw.plan_s;
    rotation(k, rots[0], false);  // warm-up
  }
  MapRow all;  // the contention of the interleaved run, shared by the three rows
  const std::vector<MapRow> fresh = lib_rows;
  quiet_measure(all, "maps " + dims_text(d), [&](MapRow&) {
    lib_rows = fresh;
    for (int i = 0; i < rotations; ++i)
      for (std::size_t k = 0; k < names.size(); ++k) rotation(k, rots[std::size_t(i)], true);
  });
  for (std::size_t k = 0; k < names.size(); ++k) {
    MapRow& r = lib_rows[k];
    r.load_before = all.load_before;
    r.load_after = all.load_after;
    r.other_cores = all.other_cores;
    r.attempts = all.attempts;
    rotation(k, R_check, false);
    std::vector<cf> y(n);
    if (names[k] == "fftw")
      std::memcpy(static_cast<void*>(y.data()), fw.out, bytes);
    else
      ctx.queue.enqueueReadBuffer(result, CL_TRUE, 0, bytes, y.data());
    r.max_rel_diff = max_rel_diff(y, ref);
    r.median_s = median(r.total_s);
    r.product_median_s = median(r.product_s);
    r.readback_median_s = median(r.readback_s);
    r.fft_median_s = median(r.fft_s);
    r.rotations_per_s = 1.0 / r.median_s;
    rows.push_back(r);
  }
  return rows;
}

// The FFT grid snapfit builds for a scene (engine/spectra/spectra.cpp: oversampling times the
// larger part grid per axis, rounded up by next_fft_size), from the parts' grids.
Dims scene_fft_dims(const std::string& path, double oversampling) {
  const snapfit::Scene scene = snapfit::load_scene(path);
  const snapfit::ScenePartGrids g = snapfit::prepare_assembly_pair(scene).grids;
  Dims d{};
  for (int a = 0; a < 3; ++a) {
    const double points = oversampling * std::max(g.part1.dims[a], g.part2.dims[a]);
    d[a] = snapfit::next_fft_size(static_cast<std::size_t>(std::ceil(points - 1e-9)));
  }
  return d;
}

// ---------------------------------------------------------------- output

void write_outputs(const std::filesystem::path& dir, const Args& args, const std::vector<TransformRow>& tr,
                   const std::vector<MapRow>& maps, const nlohmann::json& meta, const std::string& verdict) {
  std::filesystem::create_directories(dir);
  CsvFile ft(dir / "fft.csv",
             "library,direction,nx,ny,nz,points,plan_s,repeats,p50_ms,min_ms,gflops_p50,gflops_min,"
             "max_rel_diff_vs_fftw_double,load_before,load_after,other_cores");
  for (const auto& r : tr)
    ft.row(r.library, r.direction, r.dims[0], r.dims[1], r.dims[2], count_of(r.dims), r.plan_s, r.times_s.size(),
           r.p50_s * 1e3, r.min_s * 1e3, r.gflops_p50, r.gflops_min, r.max_rel_diff, r.load_before, r.load_after,
           r.other_cores);
  CsvFile mt(dir / "maps.csv",
             "path,nx,ny,nz,points,plan_s,cold_s,rotations,median_ms,product_ms,readback_ms,fft_ms,"
             "rotations_per_s,max_rel_diff_vs_fftw_double,load_before,load_after,other_cores");
  for (const auto& r : maps)
    mt.row(r.library, r.dims[0], r.dims[1], r.dims[2], count_of(r.dims), r.plan_s, finite_or_empty(r.cold_s),
           r.total_s.size(), r.median_s * 1e3, r.product_median_s * 1e3, r.readback_median_s * 1e3,
           r.fft_median_s * 1e3, r.rotations_per_s, finite_or_empty(r.max_rel_diff), r.load_before, r.load_after,
           r.other_cores);
  nlohmann::json j = meta;
  j["verdict"] = verdict;
  nlohmann::json tj = nlohmann::json::array();
  for (const auto& r : tr)
    tj.push_back({{"library", r.library},
                  {"direction", r.direction},
                  {"dims", r.dims},
                  {"points", count_of(r.dims)},
                  {"plan_s", r.plan_s},
                  {"times_ms",
                   [&] {
                     std::vector<double> ms;
                     for (double t : r.times_s) ms.push_back(t * 1e3);
                     return ms;
                   }()},
                  {"p50_ms", r.p50_s * 1e3},
                  {"min_ms", r.min_s * 1e3},
                  {"gflops_p50", r.gflops_p50},
                  {"gflops_min", r.gflops_min},
                  {"max_rel_diff_vs_fftw_double", num(r.max_rel_diff)},
                  {"load_before", r.load_before},
                  {"load_after", r.load_after},
                  {"other_cores", r.other_cores},
                  {"attempts", r.attempts}});
  j["transforms"] = tj;
  nlohmann::json mj = nlohmann::json::array();
  for (const auto& r : maps)
    mj.push_back({{"path", r.library},
                  {"dims", r.dims},
                  {"points", count_of(r.dims)},
                  {"plan_s", r.plan_s},
                  {"cold_s", num(r.cold_s)},
                  {"rotations", r.total_s.size()},
                  {"median_ms", r.median_s * 1e3},
                  {"product_median_ms", r.product_median_s * 1e3},
                  {"readback_median_ms", r.readback_median_s * 1e3},
                  {"fft_median_ms", r.fft_median_s * 1e3},
                  {"rotations_per_s", r.rotations_per_s},
                  {"max_rel_diff_vs_fftw_double", num(r.max_rel_diff)},
                  {"load_before", r.load_before},
                  {"load_after", r.load_after},
                  {"other_cores", r.other_cores},
                  {"attempts", r.attempts}});
  j["maps"] = mj;
  write_json(dir / "fft.json", j);
  const std::vector<std::string> libs = {"clfft", "vkfft", "fftw"};
  std::vector<snapfit::Chart> charts;
  for (const bool gflops : {false, true}) {
    snapfit::Chart c =
        make_chart(gflops ? "3D C2C FFT throughput (5 n log2 n / p50)" : "3D C2C FFT time per transform (p50)",
                   "points n (64^3, 128^3, scene grid)", gflops ? "GFLOP/s" : "ms per transform", true, !gflops);
    for (const auto& lib : libs)
      for (const std::string dir : {"forward", "inverse"}) {
        snapfit::Series s;
        s.label = lib + " " + dir;
        for (const auto& r : tr)
          if (r.library == lib && r.direction == dir) {
            s.x.push_back(double(count_of(r.dims)));
            s.y.push_back(gflops ? r.gflops_p50 : r.p50_s * 1e3);
          }
        if (!s.x.empty()) c.series.push_back(s);
      }
    charts.push_back(c);
  }
  {
    snapfit::Chart c = make_chart("full translational maps: rotations per second (product + inverse FFT)",
                                  "FFT grid points n", "rotations per second (median)", true, true);
    for (const std::string lib : {"clfft", "vkfft", "fftw", "full_map"}) {
      snapfit::Series s;
      s.label = lib == "full_map" ? "translational_energy_map (clFFT, real path)" : "product + " + lib + " inverse";
      for (const auto& r : maps)
        if (r.library == lib) s.x.push_back(double(count_of(r.dims))), s.y.push_back(r.rotations_per_s);
      if (!s.x.empty()) c.series.push_back(s);
    }
    charts.push_back(c);
  }
  write_charts(dir, "bench_fft: 3D FFT libraries and full maps", args.command_line, charts);
}

// ---------------------------------------------------------------- the run

// The verdict: the fastest (smallest p50) library per size and direction, the most
// rotations/s per map size, and whether every output agrees with FFTW double.
std::string verdict_text(const std::vector<Dims>& sizes, const std::vector<Dims>& map_sizes,
                         const std::vector<TransformRow>& transforms, const std::vector<MapRow>& maps) {
  std::ostringstream verdict;
  verdict << "fastest p50 per transform:";
  for (const Dims& d : sizes)
    for (const std::string dir : {"forward", "inverse"}) {
      const TransformRow* best = nullptr;
      const TransformRow* second = nullptr;
      for (const auto& r : transforms)
        if (r.dims == d && r.direction == dir) {
          if (!best || r.p50_s < best->p50_s)
            second = best, best = &r;
          else if (!second || r.p50_s < second->p50_s)
            second = &r;
        }
      if (best)
        verdict << " " << dims_text(d) << " " << dir << " " << best->library << " ("
                << (second ? fixed(second->p50_s / best->p50_s, 2) + "x ahead of " + second->library : "") << ");";
    }
  verdict << " most rotations/s (product + inverse FFT):";
  for (const Dims& d : map_sizes) {
    const MapRow* best = nullptr;
    for (const auto& r : maps)
      if (r.dims == d && r.library != "full_map" && (!best || r.rotations_per_s > best->rotations_per_s)) best = &r;
    const MapRow* fastest_fft = nullptr;
    for (const auto& r : maps)
      if (r.dims == d && r.library != "full_map" &&
          (!fastest_fft ||
           r.fft_median_s + r.readback_median_s < fastest_fft->fft_median_s + fastest_fft->readback_median_s))
        fastest_fft = &r;
    if (best)
      verdict << " " << dims_text(d) << " " << best->library << " (" << fixed(best->rotations_per_s, 1)
              << "/s; FFT part fastest: " << fastest_fft->library << " "
              << fixed((fastest_fft->fft_median_s + fastest_fft->readback_median_s) * 1e3, 1) << " ms);";
  }
  bool agree = true;
  for (const auto& r : transforms) agree = agree && r.max_rel_diff < 1e-4;
  for (const auto& r : maps)
    if (std::isfinite(r.max_rel_diff)) agree = agree && r.max_rel_diff < 1e-4;
  verdict << (agree ? " all outputs within 1e-4 of FFTW double" : " SOME OUTPUT DIFFERS BY >= 1e-4 FROM FFTW DOUBLE");
  return verdict.str();
}

void print_map_row(const MapRow& r) {
  std::cout << "  " << padr(dims_text(r.dims), 12) << padr(r.library, 10) << pad(fixed(r.plan_s, 2), 8)
            << pad(fixed(r.rotations_per_s, 2), 9) << pad(fixed(r.median_s * 1e3, 1), 9)
            << pad(r.library == "full_map" ? "-" : fixed(r.product_median_s * 1e3, 1), 9)
            << pad(r.library == "fftw" ? fixed(r.readback_median_s * 1e3, 1) : "-", 9)
            << pad(r.library == "full_map" ? "-" : fixed(r.fft_median_s * 1e3, 1), 9) << pad(sci(r.max_rel_diff), 11)
            << pad(fixed(r.other_cores, 2), 8)
            << (r.library == "full_map" ? "  (cold " + fixed(r.cold_s, 2) + " s: program, plan bake, uploads)" : "")
            << "\n"
            << std::flush;
}

int run(const Args& args) {
  RunSpan span;
  const int repeats = args.repeats > 0 ? args.repeats : (args.quick ? 5 : 30);
  const int warmup = 2;
  const int map_rotations = args.quick ? 3 : 20;
  const int map_warm_real = args.quick ? 2 : 5;
  const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
  g_quiet.enabled = !args.quick;  // --quick only records the contention
  span.announce("bench_fft", args.command_line);

  if (!fftwf_init_threads()) throw snapfit::Error("FFTW: fftwf_init_threads failed");
  fftwf_plan_with_nthreads(int(threads));
  if (!fftw_init_threads()) throw snapfit::Error("FFTW: fftw_init_threads failed");
  fftw_plan_with_nthreads(int(threads));

  const snapfit::FftLibrary lib;
  const snapfit::ComputeContext ctx =
      snapfit::make_compute_context(snapfit::select_device(snapfit::device_spec_from(args.device)));
  const auto& info = ctx.device.info;
  std::cout << "  OpenCL device (clFFT, VkFFT): " << snapfit::describe_device(info) << ", driver "
            << info.driver_version << ", " << info.compute_units << " compute units\n"
            << "  FFTW " << std::string(fftwf_version) << ", " << threads << " threads, FFTW_MEASURE; VkFFT "
            << VkFFTGetVersion() / 10000 << "." << VkFFTGetVersion() / 100 % 100 << "." << VkFFTGetVersion() % 100
            << " (OpenCL backend)\n";

  const std::string scene_path = "scenes/default.json";
  const Dims scene_dims = scene_fft_dims(scene_path, snapfit::SpectrumOptions{}.oversampling);
  std::cout << "  " << scene_path << " FFT grid (oversampling 2, next_fft_size): " << dims_text(scene_dims) << "\n";
  std::vector<Dims> sizes = {Dims{64, 64, 64}, Dims{128, 128, 128}};
  if (!args.quick && scene_dims != sizes[1] && scene_dims != sizes[0]) sizes.push_back(scene_dims);
  std::vector<Dims> map_sizes = args.quick ? std::vector<Dims>{Dims{64, 64, 64}} : sizes;
  if (args.quick) map_sizes.push_back(Dims{128, 128, 128});

  // ---- 1. transforms
  std::cout << "\n[1] 3D complex-to-complex transforms, single precision: " << repeats << " timed after " << warmup
            << " warm-up\n";
  std::cout << "  " << padr("size", 12) << padr("library", 8) << padr("dir", 9) << pad("plan s", 8) << pad("p50 ms", 10)
            << pad("min ms", 10) << pad("GFLOP/s", 9) << pad("rel diff", 11) << pad("others", 8) << "\n";
  std::vector<TransformRow> transforms;
  for (const Dims& d : sizes) {
    auto rows = bench_transforms(lib, ctx, d, warmup, repeats, 20261122u);
    for (const auto& r : rows) {
      std::cout << "  " << padr(dims_text(d), 12) << padr(r.library, 8) << padr(r.direction, 9)
                << pad(fixed(r.plan_s, 2), 8) << pad(fixed(r.p50_s * 1e3, 2), 10) << pad(fixed(r.min_s * 1e3, 2), 10)
                << pad(fixed(r.gflops_p50, 2), 9) << pad(sci(r.max_rel_diff), 11) << pad(fixed(r.other_cores, 2), 8)
                << "\n"
                << std::flush;
      transforms.push_back(r);
    }
  }

  // ---- 2. full maps
  std::cout << "\n[2] full translational maps: one rotation = spectrum_product kernel + inverse 3D FFT; "
            << map_rotations << " timed rotations per library (median); real path " << map_warm_real
            << " warm calls after a cold one\n";
  std::cout << "  " << padr("size", 12) << padr("path", 10) << pad("plan s", 8) << pad("rot/s", 9) << pad("ms", 9)
            << pad("product", 9) << pad("readback", 9) << pad("fft", 9) << pad("rel diff", 11) << pad("others", 8)
            << "\n";
  std::vector<MapRow> maps;
  for (const Dims& d : map_sizes) {
    auto rows = bench_maps(lib, ctx, d, map_rotations, map_warm_real, 4242u);
    for (const auto& r : rows) {
      print_map_row(r);
      maps.push_back(r);
    }
  }

  const std::string verdict = verdict_text(sizes, map_sizes, transforms, maps);

  span.stop();
  nlohmann::json meta = span.header("bench_fft", args.command_line, args.quick, info);
  meta["quiet_guard"] = {{"enabled", g_quiet.enabled},
                         {"threshold_cores", g_quiet.threshold},
                         {"max_retries", g_quiet.max_retries},
                         {"retries", g_quiet.retries},
                         {"waited_s", g_quiet.waited_s}};
  meta["fftw"] = {{"version", std::string(fftwf_version)}, {"threads", threads}, {"planner", "FFTW_MEASURE"}};
  meta["vkfft_version"] = VkFFTGetVersion();
  meta["scene_fft_dims"] = {{"scene", scene_path}, {"dims", scene_dims}};
  meta["method"] = {
      {"transform_time",
       "wall clock (steady_clock) around one transform incl. the wait for completion; " + std::to_string(warmup) +
           " warm-up, " + std::to_string(repeats) +
           " timed; VkFFT's input is refreshed by a device copy before each transform, outside the timed interval"},
      {"gflops", "5 n log2(n) / time, n = points"},
      {"max_rel_diff",
       "max |x - ref| / max |ref| over all points, ref = FFTW double (FFTW_ESTIMATE) of the same input"},
      {"plan_s",
       "clfft: Fft3d constructor (create + bake, both directions); vkfft: initializeVkFFT; fftw: "
       "fftwf_plan_dft_3d forward + backward with FFTW_MEASURE"},
      {"maps",
       "median over seeded random rotations of product kernel + inverse FFT (FFTW also reads the product back); "
       "full_map = engine/maps/full_map.h translational_energy_map, all modes, trilinear, warm median"}};
  const std::filesystem::path dir(args.out);
  write_outputs(dir, args, transforms, maps, meta, verdict);
  std::cout << span.end_text() << g_quiet.retries << " rows re-measured after waiting " << fixed(g_quiet.waited_s, 0)
            << " s for other processes\nwrote " << (dir / "fft.csv").string()
            << ", maps.csv, fft.json, charts.html\nverdict: " << verdict << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return guarded_main("bench_fft", [&] { return run(parse_args(argc, argv)); });
}
