#pragma once
// Shared by the stability tests (tests/test_stability_*.cpp): the default peg-and-hole
// scene made small and coarse so that the real engine (descriptors, spectra, queries)
// runs in about a second, with descriptor parameters overridable for the stiff cases.
#include <Eigen/Geometry>
#include <cmath>
#include <string>

#include "pipeline/assembly_pair.h"
#include "snapfit/scene.h"
#include "tests/test_engine_support.h"

namespace snapfit::test {

struct SmallPairParams {
  double spacing = 1.5;  // mm (the shipped scene uses 0.6)
  double padding = 3;    // mm
  double sigma = 0.5;
  double lambda_in = 3, lambda_out = 1;
  double segments = 24;  // polygon sides of peg and hole
  double oversampling = 2;
  double scale = 1;  // every length of the scene times this (units unchanged)
};

// scenes/default.json (peg in a blind hole at zero clearance) with the given grid and
// descriptor parameters; lengths optionally scaled.
inline Scene small_peg_hole_scene(const SmallPairParams& p = {}) {
  Scene s = load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/default.json");
  s.grid.spacing = p.spacing * p.scale;
  s.grid.padding = p.padding * p.scale;
  s.descriptor.sigma = p.sigma;
  s.descriptor.lambda_in = p.lambda_in;
  s.descriptor.lambda_out = p.lambda_out;
  for (PartSpec* part : {&s.part1, &s.part2}) {
    auto& n = part->procedural->numbers;
    n["segments"] = p.segments;
    for (const char* length : {"peg_radius", "hole_depth", "width", "height", "chamfer", "radius", "length"})
      if (n.count(length)) n[length] *= p.scale;
    part->pose.translation *= p.scale;
  }
  if (s.assembled_pose) s.assembled_pose->translation *= p.scale;
  for (Keyframe& k : s.trajectory.keyframes) k.pose.translation *= p.scale;
  return s;
}

// Part 2 at translation t, turned `deg` degrees about `axis`.
inline Pose pose_at(const Eigen::Vector3d& t, double deg = 0, const Eigen::Vector3d& axis = Eigen::Vector3d::UnitY()) {
  Pose p;
  p.translation = t;
  p.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(deg * M_PI / 180, axis.normalized()));
  return p;
}

inline AssemblyPair build_small_pair(const Scene& scene, double oversampling = 2, bool near_field = false) {
  const FftLibrary fft;
  PairOptions options;
  options.near_field = near_field;
  options.use_cache = false;
  options.note = [](const std::string&) {};
  options.spectrum.oversampling = oversampling;
  options.descriptors.program_cache = test_program_cache();
  return build_assembly_pair(scene, test_context(), fft, options);
}

}  // namespace snapfit::test
