#include "engine/map_fft.h"

#include "snapfit/error.h"

namespace snapfit {

std::string map_fft_name(MapFft fft) { return fft == MapFft::fftw ? "fftw" : "clfft"; }

std::vector<MapFft> map_ffts_built() {
#ifdef SNAPFIT_HAVE_FFTW
  return {MapFft::clfft, MapFft::fftw};
#else
  return {MapFft::clfft};
#endif
}

MapFft parse_map_fft(const std::string& name) {
  for (MapFft fft : map_ffts_built())
    if (map_fft_name(fft) == name) return fft;
  if (name == "fftw") throw Error("map FFT 'fftw': this build has no FFTW (install libfftw3-dev and reconfigure)");
  throw Error("unknown map FFT '" + name + "' (expected clfft or fftw)");
}

}  // namespace snapfit
