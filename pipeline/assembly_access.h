#pragma once
// What the library's own stages (tuning, the strategy choice, the loop's configuration)
// need of a public snapfit::Assembly and users do not: its device and its pipeline's
// parts, fields and spectra.
#include "engine/runtime/compute_context.h"
#include "pipeline/assembly_pair.h"
#include "snapfit/assembly.h"

namespace snapfit {

struct AssemblyAccess {
  static const AssemblyPair& pair(const Assembly& assembly);
  static const ComputeContext& context(const Assembly& assembly);
};

}  // namespace snapfit
