#include "engine/spectra/box_fft.h"

#include "snapfit/error.h"

#ifdef SNAPFIT_HAVE_FFTW
#include "engine/spectra/fftw_complex.h"
#endif

namespace snapfit {

BoxFft::BoxFft(const FftLibrary& library, const ComputeContext& ctx, std::array<std::size_t, 3> dims, FftPlace place)
    : ctx_(ctx), dims_(dims) {
#ifdef SNAPFIT_HAVE_FFTW
  const bool host = place == FftPlace::host || (place == FftPlace::automatic && ctx.device.info.type == "cpu");
#else
  if (place == FftPlace::host) throw Error("a host FFT needs FFTW, and this build has none (apt-get install libfftw3-dev)");
  const bool host = false;
#endif
  if (!host) device_ = std::make_unique<Fft3d>(library, ctx, dims);
}

void BoxFft::transform(FftDirection direction, std::vector<std::complex<float>>& box) const {
#ifdef SNAPFIT_HAVE_FFTW
  if (!device_) return fftw_complex_in_place(box, dims_, direction == FftDirection::inverse);
#endif
  if (box.size() != device_->count())
    throw Error("FFT of " + std::to_string(device_->count()) + " points given " + std::to_string(box.size()));
  cl::Buffer in(ctx_.context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, sizeof(box[0]) * box.size(), box.data());
  cl::Buffer out(ctx_.context, CL_MEM_READ_WRITE, sizeof(box[0]) * box.size());
  device_->transform(direction, in, out);
  ctx_.queue.enqueueReadBuffer(out, CL_TRUE, 0, sizeof(box[0]) * box.size(), box.data());
}

}  // namespace snapfit
