#include "engine/maps/map_fft.h"

#include "snapfit/error.h"

namespace snapfit {

std::string map_fft_name(MapFft fft) { return fft == MapFft::fftw ? "fftw" : fft == MapFft::vkfft ? "vkfft" : "clfft"; }

std::vector<MapFft> map_ffts_built() {
  std::vector<MapFft> built{MapFft::clfft};
#ifdef SNAPFIT_HAVE_FFTW
  built.push_back(MapFft::fftw);
#endif
#ifdef SNAPFIT_HAVE_VKFFT
  built.push_back(MapFft::vkfft);
#endif
  return built;
}

bool map_fft_on_device(MapFft fft) { return fft != MapFft::fftw; }

MapFft parse_map_fft(const std::string& name) {
  for (MapFft fft : map_ffts_built())
    if (map_fft_name(fft) == name) return fft;
  if (name == "fftw") throw Error("map FFT 'fftw': this build has no FFTW (install libfftw3-dev and reconfigure)");
  if (name == "vkfft") throw Error("map FFT 'vkfft': this build has no VkFFT (install libvkfft-dev and reconfigure)");
  throw Error("unknown map FFT '" + name + "' (expected clfft, fftw or vkfft)");
}

}  // namespace snapfit
