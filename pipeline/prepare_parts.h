#pragma once
// Builds both parts of a scene (load or generate, then validate) in parallel on TBB.
#include <optional>

#include "io/cad_facts.h"
#include "mesh/analytic_faces.h"
#include "mesh/mesh.h"
#include "mesh/mesh_report.h"
#include "snapfit/scene.h"

namespace snapfit {

struct PreparedPart {
  Mesh mesh;  // in the part's own frame, scene units
  std::vector<AnalyticFace> faces;  // in the mesh's frame (pipeline/part_mesh.h); none for a mesh file
  MeshReport report;
  std::optional<CadFacts> cad;  // STEP and IGES parts: what the import did
  double seconds = 0;           // wall time to load or generate and validate
};

struct PreparedParts {
  PreparedPart part1;
  PreparedPart part2;
};

// Throws snapfit::Error naming the part on failure (the first failure, if both fail).
PreparedParts prepare_parts(const Scene& scene);

}  // namespace snapfit
