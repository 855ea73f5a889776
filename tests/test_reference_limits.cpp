// Reference solver, the independent checks of docs/benchmark.md, section 5 on the reactor itself:
// Pe -> infinity (C = 2 exp(-k x / u(y))), Pe = 1e5 within 0.5% of it, monotonicity at
// Pe = 1e5, and the Pe = 10 section average against the Taylor-Aris 1D model.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "reference_test_util.hpp"

namespace adrsph::reference {
namespace {

// docs/benchmark.md, section 5: section averages of 2 exp(-k x / u(y)) at x = 25, 50, 100.
constexpr double kNoDiffusion[] = {1.38274, 1.04125, 0.62800};
// Observed agreement of the 2D Pe = 10 section averages with Taylor-Aris: see the test.
constexpr double kTaylorArisTolerance = 5e-4;  // observed: 0.012%, 0.012%, 0.024% (400x40)

// The same by quadrature (midpoint rule, 200,000 points), to check the numbers of
// docs/benchmark.md.
double no_diffusion_average(double x) {
  const int n = 200000;
  double sum = 0.0;
  for (int j = 0; j < n; ++j) {
    const double eta = -1.0 + (j + 0.5) * 2.0 / n;
    sum += 2.0 * std::exp(-1.462 * x / (200.0 * (1.0 - eta * eta)));
  }
  return sum / n;
}

TEST(ReferenceLimits, SpecNoDiffusionValuesAreTheIntegral) {
  const double xs[] = {25.0, 50.0, 100.0};
  for (int m = 0; m < 3; ++m) EXPECT_NEAR(no_diffusion_average(xs[m]), kNoDiffusion[m], 6e-6);
}

// D = 0: each row is an exact upwind-TVD march; the section averages converge to the limit.
TEST(ReferenceLimits, NoDiffusionReachesThePecletInfinityLimit) {
  const Problem p = testing::reactor(0.0);
  const Solution s = solve_steady(p, 800, 80);
  ASSERT_TRUE(s.report.converged);
  const StationTable st = station_table(s, p);
  for (int m = 0; m < 3; ++m) {
    const double rel = std::abs(st.c_mean[m] - kNoDiffusion[m]) / kNoDiffusion[m];
    std::printf("  D=0, 800x80, x=%g: %.6f vs %.5f (rel. %.1e)\n", st.x_mm[m], st.c_mean[m],
                kNoDiffusion[m], rel);
    EXPECT_LT(rel, 2e-4);
  }
}

TEST(ReferenceLimits, Pe1e5IsWithinHalfAPercentOfTheLimit) {
  const Problem p = testing::reactor(0.1);
  const Solution s = solve_steady(p, 800, 80);
  ASSERT_TRUE(s.report.converged);
  const StationTable st = station_table(s, p);
  for (int m = 0; m < 3; ++m) {
    const double rel = (st.c_mean[m] - kNoDiffusion[m]) / kNoDiffusion[m];
    std::printf("  D=0.1, 800x80, x=%g: %.6f vs %.5f (%+.3f%%)\n", st.x_mm[m], st.c_mean[m],
                kNoDiffusion[m], 100.0 * rel);
    EXPECT_LT(std::abs(rel), 5e-3);
  }
}

// Non-oscillatory at Pe = 1e5 (docs/benchmark.md, section 5; issue 4): 0 <= C <= c_in and C
// non-increasing along x on every grid line (the continuous solution is: dC/dx obeys a maximum
// principle).
TEST(ReferenceLimits, Pe1e5IsBoundedAndMonotoneAlongX) {
  const Problem p = testing::reactor(0.1);
  for (int nx : {400, 800}) {
    const Solution s = solve_steady(p, nx, nx / 10);
    ASSERT_TRUE(s.report.converged);
    double worst_rise = 0.0, lo = p.c_in, hi = 0.0;
    for (int j = 0; j < s.grid.ny; ++j)
      for (int i = 0; i < s.grid.nx; ++i) {
        lo = std::min(lo, s.at(i, j));
        hi = std::max(hi, s.at(i, j));
        if (i > 0) worst_rise = std::max(worst_rise, s.at(i, j) - s.at(i - 1, j));
      }
    std::printf("  D=0.1 %dx%d: C in [%.3e, %.9f], largest rise along x %.1e\n", nx, nx / 10, lo,
                hi, worst_rise);
    EXPECT_GE(lo, 0.0);
    EXPECT_LE(hi, p.c_in);
    EXPECT_LE(worst_rise, 1e-12);
  }
}

// Pe = 10: transverse mixing is fast, so the section average follows the 1D dispersion
// model with the Taylor-Aris coefficient K = D (1 + (2/105) (U a / D)^2), U = (2/3) u_max
// the true mean velocity, a = R (docs/benchmark.md, section 5).
TEST(ReferenceLimits, Pe10FollowsTaylorAris) {
  const Problem p = testing::reactor(1000.0);
  const Solution s = solve_steady(p, 400, 40);
  ASSERT_TRUE(s.report.converged);
  const double U = 2.0 / 3.0 * 200.0, a = 5.0;
  const double K = p.D * (1.0 + (2.0 / 105.0) * std::pow(U * a / p.D, 2));
  const testing::AxialDispersion1D model{U, K, p.k, p.length, p.c_in};
  const StationTable st = station_table(s, p);
  for (int m = 0; m < 3; ++m) {
    const double rel = (st.c_mean[m] - model(st.x_mm[m])) / model(st.x_mm[m]);
    std::printf("  Pe=10, 400x40, x=%g: %.6f, Taylor-Aris %.6f (%+.4f%%)\n", st.x_mm[m],
                st.c_mean[m], model(st.x_mm[m]), 100.0 * rel);
    EXPECT_LT(std::abs(rel), kTaylorArisTolerance);
  }
}

}  // namespace
}  // namespace adrsph::reference
