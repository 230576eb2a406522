// The scripted insertion of the peg-and-hole scenes at zero clearance through the real
// engine and the haptic loop (scheduler/haptics/assembly_session.h), in simulated time so the
// physics is deterministic: the part must end assembled, within the stated tolerance
// (one grid spacing, 1 degree), centred in the hole and upright, having felt the
// geometry on the way in. The truncated energy's minimum lies below the blind hole's
// bottom (the skeletal-density penalty is soft at lambda_in/lambda_out = 3); the rigid
// contact (scheduler/haptics/rigid_contact.h) holds the part at the floor.
#include <doctest/doctest.h>
#include <iostream>

#include "engine/query/query_engine.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/haptics/assembly_session.h"
#include "tests/shipped_engine.h"

using namespace snapfit;

namespace {

SessionResult insert(const std::string& scene_file, std::size_t modes, std::optional<double> gain = std::nullopt) {
  Scene scene = test::shipped_scene(scene_file);
  if (gain) scene.haptics.geometry_gain = *gain;
  const test::ShippedEngine shipped = test::shipped_engine(scene);
  const AssemblyPair& pair = shipped.pair;
  QueryEngine* engine = shipped.engine.get();
  const TuningResult fixed = pick_modes({TimingPoint{modes, 0, 0, 0, 1}}, scene.frame_budget_ms, 0.25);
  SessionOptions session;
  session.simulated_time = true;
  return run_scripted_assembly(scene, pair.parts.part1.mesh, pair.parts.part2.mesh, pair.spectra.spacing, *engine, fixed, session);
}

double peak_geometric_force(const SessionResult& r) {
  double peak = 0;
  for (const FrameRecord& f : r.loop.log) peak = std::max(peak, f.geometric.force.norm());
  return peak;
}

}  // namespace

TEST_CASE("scripted assembly: the zero-clearance peg ends assembled, 6-DOF and translation-only") {
  test::CacheDirScope cache;  // fields and spectra computed here, shared by both scenes
  for (const char* file : {"default.json", "peg_hole_translation.json"}) {
    CAPTURE(file);
    const SessionResult r = insert(file, 4096);
    std::cout << file << ": final error " << r.final_error.position << " mm, " << r.final_error.angle_deg
              << " deg; gain " << r.geometry_gain << " N/unit; peak geometric force " << peak_geometric_force(r)
              << " N\n";
    CHECK(r.loop.frames == 5500);  // 4.5 s of trajectory + 1 s settling at 1 kHz
    CHECK(r.loop.misses == 0);     // simulated time: no frame takes time
    CHECK(r.loop.flagged_frames == 0);
    CHECK(r.position_tolerance == doctest::Approx(0.6));
    CHECK(r.assembled);
    CHECK(r.final_error.position < r.position_tolerance);
    CHECK(r.final_error.angle_deg < r.angle_tolerance_deg);
    // Centred by the fit: lateral offset and tilt far below the tolerances.
    const Eigen::Vector3d offset = r.loop.final_part.pose.translation - r.target.translation;
    CHECK(offset.head<2>().norm() < 0.05);
    CHECK(r.final_error.angle_deg < 0.1);
    // At rest the coupling balances the geometric pull and the floor's contact:
    // k d + gain F_engine + F_contact = 0.
    const FrameRecord& last = r.loop.log.back();
    const Eigen::Vector3d stretch = 800 * 1e-3 * (last.device.translation - last.part.translation);
    CHECK((stretch + last.geometric.force + last.contact.force).norm() <
          1e-3 * (last.geometric.force.norm() + last.contact.force.norm()) + 1e-6);
    // The rigid contact holds the part at the fit: within the contact's skin (0.07 mm)
    // and a few hundredths more, not sunk where the truncated energy is lowest.
    CHECK(std::abs(offset.z()) < 0.1);
    // The geometry was felt: the peak geometric force is a sizeable fraction of the
    // coupling force at one grid spacing (0.48 N), not a negligible one.
    CHECK(peak_geometric_force(r) > 0.1 * 800 * 0.6e-3);
    for (const FrameRecord& f : r.loop.log) {
      REQUIRE(f.sent.force.allFinite());
      CHECK(f.sent.force.norm() <= 10.0 + 1e-12);
    }
  }
}
