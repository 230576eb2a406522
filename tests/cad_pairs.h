#pragma once
// Six pairs of CAD parts with what real assemblies have (a screw head seating on a face, a
// ring slid 100 mm along a shaft, a square peg, a D-shaft, two pins into two holes, fillets
// and a groove), built with OpenCASCADE's modelling API and written as STEP files, with a
// scene each (tests/tools/make_cad_pairs.cpp writes scenes/parts/cad/ and scenes/cad/).
//
// Every pair is assembled along -z of part 1's frame: part 2 moves straight down into its
// seat, and the assembled pose is a translation. Lengths in mm.
// The dimensions are here so that tests/test_cad_pairs.cpp can check the files against
// closed-form volumes and contacts.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace snapfit::test {

// A cheese-head screw (a flat bearing face under a head whose top edge is rounded, a
// chamfered tip) through the right-hand hole of a link rod with round ends and two holes.
struct ScrewRodDims {
  double head_radius = 6, head_height = 4, head_fillet = 1.5;  // bearing face at z = 0 of the screw
  double shank_radius = 3, shank_length = 12, tip_chamfer = 0.5;
  double rod_half_length = 15, rod_width = 14, rod_thickness = 8;  // hole centres at x = +-half length
  double hole_radius = 4;                                           // 1 mm of radial clearance
};

// A ring (chamfered bore) slid down a long shaft (chamfered top) to a shoulder at z = 0.
struct RingShaftDims {
  double shaft_radius = 5, shaft_length = 110, shaft_chamfer = 0.5;
  double shoulder_radius = 9, shoulder_height = 6;  // the shoulder below z = 0
  double ring_inner = 5, ring_outer = 9, ring_height = 8, bore_chamfer = 0.5;  // zero clearance
};

// A square peg (chamfered bottom edges) into a blind square hole with a chamfered entry.
struct SquarePegDims {
  double peg_side = 8, peg_length = 20, peg_chamfer = 0.5;
  double clearance = 0.1;  // per side
  double block_side = 24, block_height = 20, hole_depth = 14, entry_chamfer = 0.5;
};

// A D-shaft (a cylinder with one flat) into a blind D-hole.
struct DShaftDims {
  double radius = 5, flat = 3.5, length = 20;  // the flat at x = `flat`
  double clearance = 0.2;                      // on the radius and on the flat
  double block_side = 24, block_height = 20, hole_depth = 15;
};

// A plate with two pins (chamfered tips) into a block with two blind holes.
struct TwoPinDims {
  double plate_length = 40, plate_width = 16, plate_thickness = 4;
  double pin_radius = 2.5, pin_length = 8, pin_chamfer = 0.3, pin_offset = 12;  // pins at x = +-offset
  double clearance = 0.05;
  double block_height = 12, hole_depth = 10;
};

// A shaft with a rounded tip and a retaining-ring groove under a head with a rounded top
// edge, into a collar (a tube) with a chamfered entry.
struct GroovedShaftDims {
  double shaft_radius = 5, shaft_length = 24, tip_fillet = 1;  // the head's bearing face at z = 0
  double groove_top = -14, groove_width = 2, groove_depth = 0.8;  // the groove spans z in [top - width, top]
  double head_radius = 8, head_height = 4, head_fillet = 1;
  double clearance = 0.5;
  double collar_outer = 12, collar_height = 16, entry_chamfer = 1;
};

// What a pair's scene and its benchmark need.
struct CadPairInfo {
  std::string name;   // file stem: scenes/cad/<name>.json, scenes/parts/cad/<name>_<part>.step
  std::string title;  // the scene's name
  std::string part1, part2;
  double clearance = 0;  // radial, mm
  double entry = 0;      // part 2's travel from first reaching part 1 to the assembled pose (mm, along -z)
  double engaged = 0;    // length of the fit along the axis, for the play angle
  double spacing = 0.6;  // the scene's grid spacing
  Eigen::Vector3d assembled = Eigen::Vector3d::Zero();  // part 2's translation when assembled
};

// The six pairs, in a fixed order.
const std::vector<CadPairInfo>& cad_pairs();

// Writes the pair's two STEP files, <dir>/<name>_1.step and <dir>/<name>_2.step (each one
// solid named as its part, millimetres); returns their paths.
std::vector<std::string> write_cad_pair(const CadPairInfo& pair, const std::string& dir);

// The pair's scene file (docs/scenes.md) with its parts at `parts_folder` (relative to the
// scene's folder): a trajectory that starts above and off the axis, tilted, and ends at
// the assembled pose.
std::string cad_pair_scene(const CadPairInfo& pair, const std::string& parts_folder);

}  // namespace snapfit::test
