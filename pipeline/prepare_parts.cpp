#include "pipeline/prepare_parts.h"

#include <chrono>
#include <exception>
#include <tbb/parallel_invoke.h>

#include "pipeline/part_mesh.h"

namespace snapfit {
namespace {

PreparedPart prepare(const PartSpec& spec, const Scene& scene) {
  const auto start = std::chrono::steady_clock::now();
  PreparedPart part;
  PartMesh built = build_part_mesh(spec, scene);
  part.mesh = std::move(built.mesh);
  part.cad = std::move(built.cad);
  part.report = validate_mesh(part.mesh);
  part.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return part;
}

}  // namespace

PreparedParts prepare_parts(const Scene& scene) {
  PreparedParts parts;
  std::exception_ptr error1, error2;
  tbb::parallel_invoke(
      [&] {
        try {
          parts.part1 = prepare(scene.part1, scene);
        } catch (...) {
          error1 = std::current_exception();
        }
      },
      [&] {
        try {
          parts.part2 = prepare(scene.part2, scene);
        } catch (...) {
          error2 = std::current_exception();
        }
      });
  if (error1) std::rethrow_exception(error1);
  if (error2) std::rethrow_exception(error2);
  return parts;
}

}  // namespace snapfit
