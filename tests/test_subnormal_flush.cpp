// core/subnormal_flush.h: subnormal floats read and made as zero in the calling thread while
// a SubnormalFlush lives, the thread's setting back after; and the default peg's query at a
// pose whose offsets from the fit are subnormal in float equals its query at the fit.
#include <cmath>
#include <doctest/doctest.h>
#include <limits>
#include <optional>

#include "core/subnormal_flush.h"
#include "tests/shipped_engine.h"

using namespace snapfit;

namespace {

// Read through volatiles so that the compiler folds nothing: the products are the CPU's.
float product(float a, float b) {
  volatile float x = a, y = b;
  return x * y;
}
double product(double a, double b) {
  volatile double x = a, y = b;
  return x * y;
}

}  // namespace

#if defined(__x86_64__) || defined(__i386__) || defined(__aarch64__)
TEST_CASE("subnormal flush: subnormals are zero inside, the thread's setting back after") {
  const float tiny = 1e-39f;  // below float's smallest normal, 1.18e-38
  REQUIRE(std::fpclassify(tiny) == FP_SUBNORMAL);
  REQUIRE(product(tiny, 1.0f) != 0.0f);      // the default: subnormals kept
  REQUIRE(product(1e-20f, 1e-20f) != 0.0f);  // 1e-40: a subnormal result
  {
    const SubnormalFlush flush;
    CHECK(product(tiny, 1.0f) == 0.0f);      // a subnormal read as zero
    CHECK(product(1e-20f, 1e-20f) == 0.0f);  // a subnormal result made zero
    CHECK(product(1e-300, 1e-10) == 0.0);    // double too
    CHECK(product(1e-19f, 1e-19f) == doctest::Approx(1e-38f).epsilon(1e-6));  // normal values untouched
    CHECK(product(3.0f, 0.5f) == 1.5f);
  }
  CHECK(product(tiny, 1.0f) == doctest::Approx(tiny));
  CHECK(product(1e-20f, 1e-20f) != 0.0f);
  CHECK(std::fpclassify(product(1e-300, 1e-10)) == FP_SUBNORMAL);
}
#endif

TEST_CASE("subnormal flush: a pose at rest at the default peg's fit queries as the fit itself") {
  const test::ShippedEngine s = test::shipped_engine(test::shipped_scene("default.json"));
  REQUIRE(!s.pair.scene.trajectory.keyframes.empty());
  const Pose fit = s.pair.scene.trajectory.keyframes.back().pose;
  s.engine->set_modes(std::min<std::size_t>(16384, s.engine->max_modes()));
  const QueryResult at_fit = s.engine->query(fit);
  REQUIRE(at_fit.flags == query_ok);
  // A part settling at the fit approaches it exponentially: offsets of 1e-40 are subnormal
  // once in float, and their products with the frequencies fall further still.
  for (double offset : {1e-21, 1e-35, 1e-40, 1e-44}) {
    Pose resting = fit;
    resting.translation += Eigen::Vector3d(offset, -0.5 * offset, 0.2 * offset);
    resting.rotation = (fit.rotation * Eigen::Quaterniond(1, 0.7 * offset, -1.4 * offset, 0.004 * offset)).normalized();
    for (int flushed = 0; flushed < 2; ++flushed) {
      std::optional<SubnormalFlush> flush;
      if (flushed) flush.emplace();
      const QueryResult r = s.engine->query(resting);
      CAPTURE(offset);
      CAPTURE(flushed);
      CHECK(r.flags == query_ok);
      const double scale = std::abs(at_fit.energy) + 1e-30;
      CHECK(std::abs(r.energy - at_fit.energy) <= 1e-6 * scale);
      CHECK((r.force - at_fit.force).norm() <= 1e-5 * (at_fit.force.norm() + 1e-6 * scale));
      CHECK((r.torque - at_fit.torque).norm() <= 1e-5 * (at_fit.torque.norm() + 1e-6 * scale));
    }
  }
}
