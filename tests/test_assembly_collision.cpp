// truncation_tails and collision_verdict (include/snapfit/collision.h) on a public
// Assembly of an indicator scene: the bound's shape (zero at every mode, non-increasing,
// Cauchy-Schwarz on the tails) and the one-sided verdict at a deep overlap.
#include <cmath>
#include <doctest/doctest.h>

#include "snapfit/assembly.h"
#include "snapfit/collision.h"
#include "tests/shipped_engine.h"

using namespace snapfit;

TEST_CASE("collision: the assembly's tails bound the truncated overlap, a deep overlap is proven") {
  AssemblyOptions options;
  options.note = [](const std::string&) {};
  const Assembly assembly(indicator_scene(test::shipped_scene("collision_only.json")), options);
  const TruncationTails tails = truncation_tails(assembly);
  auto engine = assembly.make_query_engine();
  const std::size_t all = engine->max_modes();
  REQUIRE(tails.tail1.size() == all + 1);
  REQUIRE(tails.tail2.size() == all + 1);
  CHECK(tails.dw > 0);
  CHECK(tails.bound(all) == doctest::Approx(0).epsilon(1e-12));
  // The bound is Cauchy-Schwarz on the tails: non-increasing in m'.
  double previous = tails.bound(1);
  for (std::size_t m = 2; m <= all; m = m * 3 / 2 + 1) {
    CHECK(tails.bound(m) <= previous * (1 + 1e-9));
    previous = tails.bound(m);
  }
  CHECK(tails.bound(1) == doctest::Approx(tails.dw * std::sqrt(tails.tail1[1] * tails.tail2[1])));

  // The peg 10 mm down the hole but 8 mm off its axis, deep in the block's wall.
  engine->set_modes(all);
  Pose pose;
  pose.translation = Eigen::Vector3d(8, 0, -10);
  const QueryResult r = engine->query(pose);
  const CollisionVerdict v = collision_verdict(r, tails);
  CHECK(v.overlap == doctest::Approx(r.energy));
  CHECK(v.bound == doctest::Approx(tails.bound(r.modes)));
  CHECK(v.collides == (v.overlap > v.bound));
  CHECK(v.collides);
}
