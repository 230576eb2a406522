#include "engine/runtime/kernel_sources.h"

#include "snapfit/error.h"

namespace snapfit {

std::string kernel_source(const std::string& name) {
  std::string known;
  for (const KernelSource& source : embedded_kernel_sources()) {
    if (name == source.name) return source.text;
    known += known.empty() ? "" : ", ";
    known += source.name;
  }
  throw Error("no embedded kernel source named '" + name + "' (known: " + known + ")");
}

}  // namespace snapfit
