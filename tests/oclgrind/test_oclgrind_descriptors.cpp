// The descriptor kernels (kernels/unsigned_distance.cl, winding_number.cl,
// skeletal_density.cl) in every variant the engine builds, on Oclgrind with its checks on
// (tests/oclgrind/oclgrind_support.h) and on PoCL: no report, and the same fields within
// float rounding (docs/portability.md).
#include <algorithm>
#include <cmath>
#include <doctest/doctest.h>
#include <limits>

#include "tests/oclgrind/oclgrind_cases.h"
#include "tests/oclgrind/oclgrind_support.h"
#include "tests/test_engine_support.h"

namespace snapfit::test {
namespace {

double max_abs(const std::vector<float>& v) {
  double m = 0;
  for (float x : v) m = std::max(m, double(std::abs(x)));
  return m;
}

// Largest |a - b| beyond the slack the two results' own error bounds allow (0 where
// either bound covers the difference): the fields are quadratures whose accept/split
// decisions may differ at a threshold by a rounding, and each result is within its
// bound of the exact value, so they differ by at most both bounds plus rounding.
double excess(const std::vector<float>& a, const std::vector<float>& b, const std::vector<float>* bound_a,
              const std::vector<float>* bound_b) {
  REQUIRE(a.size() == b.size());
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double slack = bound_a ? double((*bound_a)[i]) + double((*bound_b)[i]) : 0.0;
    worst = std::max(worst, std::abs(double(a[i]) - double(b[i])) - slack);
  }
  return worst;
}

// Each field as PoCL computes it against Oclgrind's: within float rounding of the largest
// value (the sums hold up to a few hundred terms) beyond the quadrature bounds.
void compare_fields(const DescriptorFields& pocl, const DescriptorFields& oclgrind, const std::string& name) {
  const double eps = std::numeric_limits<float>::epsilon();
  const double dw = excess(pocl.winding, oclgrind.winding, &pocl.winding_bound, &oclgrind.winding_bound);
  const double dwb = excess(pocl.winding_bound, oclgrind.winding_bound, nullptr, nullptr);
  MESSAGE(name << ": beyond the bounds, PoCL - Oclgrind: w " << dw << " (raw difference "
               << excess(pocl.winding, oclgrind.winding, nullptr, nullptr) << "), w bound " << dwb);
  CHECK_MESSAGE(dw <= 64 * eps, name << ": winding numbers differ by " << dw);
  CHECK_MESSAGE(dwb <= 64 * eps * std::max(1.0, max_abs(pocl.winding_bound)), name << ": w bounds differ by " << dwb);
  if (pocl.skeletal_density.empty()) return;
  const double dx = excess(pocl.signed_distance, oclgrind.signed_distance, nullptr, nullptr);
  const double ds =
      excess(pocl.skeletal_density, oclgrind.skeletal_density, &pocl.density_bound, &oclgrind.density_bound);
  MESSAGE(name << ": xi " << dx << " (largest " << max_abs(pocl.signed_distance) << "), s " << ds << " (largest "
               << max_abs(pocl.skeletal_density) << "; raw difference "
               << excess(pocl.skeletal_density, oclgrind.skeletal_density, nullptr, nullptr) << ")");
  CHECK_MESSAGE(dx <= 16 * eps * max_abs(pocl.signed_distance), name << ": signed distances differ by " << dx);
  CHECK_MESSAGE(ds <= 64 * eps * max_abs(pocl.skeletal_density), name << ": skeletal densities differ by " << ds);
}

void run_cases(bool points_and_brute_force) {
  for (const DescriptorCase& c : descriptor_cases()) {
    if ((c.at_points || c.options.brute_force_density) != points_and_brute_force) continue;
    OclgrindSession session(checks_for(c.kernels));
    const DescriptorFields oclgrind = run_descriptor_case(session.context(), c);
    const std::string reports = session.take_reports();
    CHECK_MESSAGE(reports.empty(), c.name << ": Oclgrind reported:\n" << reports);
    compare_fields(run_descriptor_case(test_context(), c), oclgrind, c.name);
  }
}

}  // namespace

TEST_CASE("oclgrind: descriptor kernels on grids, every packet width and launch shape: clean, and equal to PoCL") {
  run_cases(false);
}

TEST_CASE("oclgrind: descriptor kernels at explicit points and the brute-force density: clean, and equal to PoCL") {
  run_cases(true);
}

}  // namespace snapfit::test
