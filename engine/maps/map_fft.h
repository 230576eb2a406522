#pragma once
// The inverse FFT behind a full translational map (engine/maps/full_map.h), one of those this
// build has: clFFT on the OpenCL device (complex-to-complex over every node; always
// built), FFTW on the host (complex-to-real over the half spectrum; when CMake finds
// FFTW) or VkFFT on the OpenCL device (complex-to-complex like clFFT; when CMake finds
// vkFFT.h). Which is faster depends on the device and the size: engine/maps/map_fft_choice.h
// measures them.
#include <string>
#include <vector>

namespace snapfit {

enum class MapFft { clfft, fftw, vkfft };

std::string map_fft_name(MapFft fft);  // "clfft", "fftw", "vkfft"
// The name's backend; throws snapfit::Error naming it when unknown or not in this build.
MapFft parse_map_fft(const std::string& name);
std::vector<MapFft> map_ffts_built();  // clfft first, then fftw, vkfft
// True for the backends whose maps are on the device (clFFT, VkFFT): their minima are
// found there (engine/maps/device_minima.h).
bool map_fft_on_device(MapFft fft);

}  // namespace snapfit
