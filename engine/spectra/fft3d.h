#pragma once
// 3D complex-to-complex FFTs on the OpenCL device through clFFT (seed 000 sec. 3.2,
// eq. 13-14): forward F_k = sum_i f_i exp(-2 pi i k.i/N), inverse unnormalized
// (clFFT scales the backward transform by 1/N by default; we turn that off so the
// caller applies the physical dV / dw factors in one place). Data layout: interleaved
// complex float, x fastest (core/grid.h).
//
// clFFT keeps library-wide state (clfftSetup/clfftTeardown); FftLibrary owns it for
// the process and must outlive every plan. Plans are baked once per (context, dims)
// and reused; baking compiles kernels and takes seconds on PoCL.
#include <CL/opencl.hpp>
#include <array>
#include <cstddef>
#include <memory>

#include "engine/runtime/compute_context.h"

namespace snapfit {

// The smallest n' >= n whose prime factors are all in {2, 3, 5, 7} (clFFT's fast radices).
std::size_t next_fft_size(std::size_t n);
// The same, even.
std::size_t next_even_fft_size(std::size_t n);

class FftLibrary {
 public:
  FftLibrary();   // clfftSetup; throws snapfit::Error on failure
  ~FftLibrary();  // clfftTeardown
  FftLibrary(const FftLibrary&) = delete;
  FftLibrary& operator=(const FftLibrary&) = delete;
};

enum class FftDirection { forward, inverse };

class Fft3d {
 public:
  // dims: points along x, y, z; each must have only factors 2, 3, 5, 7. `batch`
  // transforms of count() points each, one after the other in the buffers, per call.
  // Throws snapfit::Error naming the dims and the device when the plan cannot be baked.
  Fft3d(const FftLibrary& library, const ComputeContext& ctx, std::array<std::size_t, 3> dims, std::size_t batch = 1);
  ~Fft3d();
  Fft3d(const Fft3d&) = delete;
  Fft3d& operator=(const Fft3d&) = delete;

  std::array<std::size_t, 3> dims() const { return dims_; }
  std::size_t count() const { return dims_[0] * dims_[1] * dims_[2]; }
  std::size_t batch() const { return batch_; }

  // Out-of-place transform of batch() x count() complex floats; blocks until done.
  void transform(FftDirection direction, const cl::Buffer& input, const cl::Buffer& output) const;
  // The same transform enqueued on the context's queue without waiting (later commands
  // on that in-order queue see its result).
  void enqueue(FftDirection direction, const cl::Buffer& input, const cl::Buffer& output) const;

 private:
  const ComputeContext& ctx_;
  std::array<std::size_t, 3> dims_;
  std::size_t batch_ = 1;
  std::size_t plan_ = 0;  // clfftPlanHandle
};

}  // namespace snapfit
