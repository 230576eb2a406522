#pragma once
// The inverse FFT behind a full translational map (engine/full_map.h), one of those this
// build has: clFFT on the OpenCL device (complex-to-complex over every node; always
// built) or FFTW on the host (complex-to-real over the half spectrum; when CMake finds
// FFTW). Which is faster depends on the device and the size: engine/map_fft_choice.h
// measures them.
#include <string>
#include <vector>

namespace snapfit {

enum class MapFft { clfft, fftw };

std::string map_fft_name(MapFft fft);  // "clfft", "fftw"
// The name's backend; throws snapfit::Error naming it when unknown or not in this build.
MapFft parse_map_fft(const std::string& name);
std::vector<MapFft> map_ffts_built();  // clfft first

}  // namespace snapfit
