// The "assembled" verdict (scheduler/haptics/assembly_verdict.h, judge_session_end): a pose that
// the part's symmetry makes equal to the assembled one counts, one that only looks close
// by its angle does not, and the pose's own tolerances still count as before.
#include <cmath>
#include <doctest/doctest.h>

#include "scheduler/haptics/assembly_session.h"
#include "scheduler/haptics/assembly_verdict.h"
#include "snapfit/error.h"
#include "tests/test_meshes.h"

using namespace snapfit;

namespace {

constexpr double kPositionTolerance = 0.6, kAngleToleranceDeg = 1;

Pose turned(const Eigen::Vector3d& axis, double degrees) {
  Pose p;
  p.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(degrees * M_PI / 180, axis.normalized()));
  return p;
}

Pose fit() {
  Pose p;
  p.translation = Eigen::Vector3d(0, 0, -20);  // scenes/default.json's assembled pose
  return p;
}

// The default scene's peg (radius 5, length 30, 64 segments) and a square peg as wide.
Mesh round_peg() { return test::peg_mesh(5, 30); }
Mesh square_peg() { return test::box_mesh(Eigen::Vector3d(-5, -5, 0), Eigen::Vector3d(5, 5, 30)); }

// A finished session's result, its loop ending with part 2 at `final_pose`, judged.
SessionResult judged_session(const Mesh& part2, const Pose& final_pose, bool has_assembled_pose = true) {
  Scene scene;
  if (has_assembled_pose) scene.assembled_pose = fit();
  SessionResult out;
  out.target = fit();
  out.position_tolerance = kPositionTolerance;
  out.angle_tolerance_deg = kAngleToleranceDeg;
  out.loop.final_part.pose = final_pose;
  judge_session_end(out, scene, part2);
  return out;
}

}  // namespace

TEST_CASE("assembly verdict: a round peg turned 90 degrees about its axis at the fit is assembled") {
  const SessionResult run = judged_session(round_peg(), fit() * turned(Eigen::Vector3d::UnitZ(), 90));
  INFO("angle ", run.final_error.angle_deg, " deg, surface ", run.surface_deviation);
  CHECK(run.final_error.angle_deg == doctest::Approx(90));  // the pose alone says no
  CHECK(run.final_error.position < 1e-12);
  CHECK(run.surface_deviation < 1e-9);
  CHECK(run.evaluated);
  CHECK(run.assembled);
}

TEST_CASE("assembly verdict: a square peg turned 10 degrees about its axis at the fit is not assembled") {
  // Its corners move 5 (sqrt 2 sin 55 - 1) = 0.79 mm, past the 0.6 mm tolerance.
  const SessionResult run = judged_session(square_peg(), fit() * turned(Eigen::Vector3d::UnitZ(), 10));
  INFO("angle ", run.final_error.angle_deg, " deg, surface ", run.surface_deviation);
  CHECK(run.surface_deviation == doctest::Approx(5 * (std::sqrt(2.0) * std::sin(55 * M_PI / 180) - 1)).epsilon(1e-6));
  CHECK(std::abs(run.surface_deviation_at.x()) == doctest::Approx(5));  // at a corner
  CHECK(std::abs(run.surface_deviation_at.y()) == doctest::Approx(5));
  CHECK(!run.assembled);
  // Turned 90 degrees it is back on its own surface.
  CHECK(judged_session(square_peg(), fit() * turned(Eigen::Vector3d::UnitZ(), 90)).assembled);
}

TEST_CASE("assembly verdict: a peg short of the fit, tilted or off to the side is judged by either rule") {
  const Mesh peg = round_peg();
  Pose shallow = fit();
  shallow.translation.z() += 0.4;  // within 0.6 mm: the pose says yes, the surface moved 0.4 mm
  const SessionResult a = judged_session(peg, shallow);
  CHECK(a.surface_deviation == doctest::Approx(0.4).epsilon(1e-9));
  CHECK(a.assembled);
  shallow.translation.z() += 0.4;  // 0.8 mm: neither
  CHECK(!judged_session(peg, shallow).assembled);

  // Tilted 0.9 degrees about the peg's foot: within the angle tolerance, so assembled by
  // its pose, though its top swings 30 x 0.0157 = 0.47 mm.
  const SessionResult tilted = judged_session(peg, fit() * turned(Eigen::Vector3d::UnitX(), 0.9));
  CHECK(tilted.surface_deviation == doctest::Approx(30 * 0.9 * M_PI / 180).epsilon(0.02));
  CHECK(tilted.assembled);
  // 1.5 degrees: 0.79 mm at the top and past the angle tolerance: not assembled.
  CHECK(!judged_session(peg, fit() * turned(Eigen::Vector3d::UnitX(), 1.5)).assembled);
}

TEST_CASE("assembly verdict: without an assembled pose nothing is judged, though the surface is measured") {
  const SessionResult run = judged_session(round_peg(), fit() * turned(Eigen::Vector3d::UnitZ(), 90), false);
  CHECK(!run.evaluated);
  CHECK(!run.assembled);
  CHECK(run.surface_deviation < 1e-9);
}

TEST_CASE("assembly verdict: the judge applies the same rule to a pose, or to measures made already") {
  const AssemblyJudge judge(round_peg(), fit(), kPositionTolerance, kAngleToleranceDeg);
  const AssemblyVerdict quarter = judge.judge(fit() * turned(Eigen::Vector3d::UnitZ(), 90));
  CHECK(quarter.assembled);
  CHECK(quarter.pose.angle_deg == doctest::Approx(90));
  PoseError far;
  far.position = 5, far.angle_deg = 30;
  CHECK(judge.assembled(far, 0.59));
  CHECK(!judge.assembled(far, 0.61));
  PoseError close;
  close.position = 0.59, close.angle_deg = 0.99;
  CHECK(judge.assembled(close, 100));
  CHECK_THROWS_AS(AssemblyJudge(Mesh{}, fit(), kPositionTolerance, kAngleToleranceDeg), Error);
}
