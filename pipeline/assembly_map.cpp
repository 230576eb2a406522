// translational_energy_map (include/snapfit/maps.h) on a public Assembly's device and
// spectra (engine/maps/full_map.h).
#include "engine/maps/full_map.h"
#include "pipeline/assembly_access.h"
#include "snapfit/assembly.h"
#include "snapfit/maps.h"

namespace snapfit {

TranslationMap translational_energy_map(const Assembly& assembly, const TranslationMapRequest& request) {
  const FftLibrary fft;  // clFFT's library state, only while the map is computed
  return translational_energy_map(fft, AssemblyAccess::context(assembly), AssemblyAccess::pair(assembly).spectra,
                                  request.rotation, Interpolation::tricubic, request.modes);
}

}  // namespace snapfit
