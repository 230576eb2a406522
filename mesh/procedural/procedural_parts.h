#pragma once
// Parts that snapfit generates itself, as watertight triangle meshes with outward
// normals, so tests and benchmarks have exact, known geometry:
//   peg              a cylinder along +z (bottom face at z = 0), optional tip chamfer
//   hole_block       a box (top face at z = 0) with a cylindrical hole down -z that fits
//                    a peg of `peg_radius` at a given `clearance`, optional entry chamfer
//   three_peg_base   a base slab with three pegs of different diameters whose bases are
//                    filleted (curved, toroidal mating faces), in the spirit of seed 000 Fig. 4
//   three_peg_cover  its exact complement at zero clearance (holes with rounded entries)
// Every parameter is described in docs/scenes.md.
//
// All four are regular N-gon approximations (N = `segments`, vertices at angles
// 2*pi*i/N), so their volumes have exact polygonal closed forms. Meshes are indexed
// (each vertex once), watertight, with outward normals (counter-clockwise from outside).
// Assembled poses (part 2 relative to part 1, pure translations):
//   peg in hole_block: translation (0, 0, -hole_depth) puts the peg fully inserted, its
//     bottom face on the hole's bottom (flush with the block's bottom for a through hole);
//     the parallel flat faces of peg and hole are then exactly `clearance` apart.
//   three_peg_cover on three_peg_base: the identity; base and cover share the mating
//     surface's vertices and together fill the box [footprint] x [-base_thickness, top].
#include <string>

#include "mesh/analytic_faces.h"
#include "mesh/mesh.h"
#include "snapfit/scene.h"

namespace snapfit {

// Throws snapfit::Error("<field>: <problem> (got <value>)") for an unknown type, an
// unknown or missing parameter, or a value out of range. Callers prefix the field path.
void check_procedural_spec(const ProceduralPartSpec& spec);

// Builds the part (checks the spec first).
Mesh make_procedural_part(const ProceduralPartSpec& spec);

// The analytic faces the part's mesh tessellates (mesh/analytic_faces.h), in the part's
// frame: planes, cylinders and cones of the peg and the hole block; planes (the flat
// mating face with the three fillets' discs cut out), cylinders and tori (the fillets,
// whose points stay unlabelled) of the three-peg pair. Checks the spec first.
std::vector<AnalyticFace> procedural_part_faces(const ProceduralPartSpec& spec);

}  // namespace snapfit
