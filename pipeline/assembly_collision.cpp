// truncation_tails (include/snapfit/collision.h) of a public Assembly's spectra.
#include "engine/query/collision_predicate.h"
#include "pipeline/assembly_access.h"
#include "snapfit/assembly.h"
#include "snapfit/collision.h"

namespace snapfit {

TruncationTails truncation_tails(const Assembly& assembly) {
  return truncation_tails(AssemblyAccess::pair(assembly).spectra);
}

}  // namespace snapfit
