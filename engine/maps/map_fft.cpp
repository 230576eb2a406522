#include "engine/maps/map_fft.h"

#include "core/name_table.h"
#include "snapfit/error.h"

namespace snapfit {

namespace {

const std::pair<MapFft, const char*> kMapFfts[] = {
    {MapFft::clfft, "clfft"}, {MapFft::fftw, "fftw"}, {MapFft::vkfft, "vkfft"}};

}  // namespace

std::string map_fft_name(MapFft fft) { return name_in(kMapFfts, fft); }

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
  const std::optional<MapFft> fft = value_in(kMapFfts, name);
  if (!fft) throw Error("unknown map FFT '" + name + "' (expected " + names_in(kMapFfts) + ")");
  for (MapFft built : map_ffts_built())
    if (built == *fft) return built;
  if (*fft == MapFft::fftw) throw Error("map FFT 'fftw': this build has no FFTW (install libfftw3-dev and reconfigure)");
  throw Error("map FFT 'vkfft': this build has no VkFFT (install libvkfft-dev and reconfigure)");
}

}  // namespace snapfit
