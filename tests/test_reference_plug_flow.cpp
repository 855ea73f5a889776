// Reference solver against a closed form (issue 4): plug flow u = U with axial diffusion
// and reaction, Dirichlet inlet, zero-gradient outlet. No transverse variation, so every
// row must follow C(x) = A e^{m1 x} + B e^{m2 x} (reference_test_util.hpp derives A, B).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "reference_test_util.hpp"

namespace adrsph::reference {
namespace {

Problem plug_flow(double U, double D) {
  Problem p;
  p.D = D;
  p.velocity = [U](double) { return U; };
  return p;
}

// Max relative error over all cells against the closed form at the cell centres.
double max_relative_error(const Problem& p, const testing::AxialDispersion1D& exact, int nx) {
  const Solution s = solve_steady(p, nx, 4);
  EXPECT_TRUE(s.report.converged);
  double err = 0.0;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < 4; ++j) {
      const double ce = exact(s.grid.xc(i));
      err = std::max(err, std::abs(s.at(i, j) - ce) / ce);
    }
  return err;
}

TEST(ReferencePlugFlow, MatchesClosedFormAtSecondOrder) {
  // Pe = U L / D = 100 and 1000; at D = 10 the outlet layer (thickness D / U = 0.1 mm,
  // amplitude ~1e-3 of C) needs dx <= 0.0625 to show the asymptotic order.
  for (double D : {100.0, 10.0}) {
    const double U = 100.0;
    const Problem p = plug_flow(U, D);
    const testing::AxialDispersion1D exact{U, D, p.k, p.length, p.c_in};
    const double e1 = max_relative_error(p, exact, 800);
    const double e2 = max_relative_error(p, exact, 1600);
    std::printf("  plug flow D=%g: max rel. error %.3e (800 cells), %.3e (1600), order %.2f\n", D,
                e1, e2, std::log2(e1 / e2));
    EXPECT_LT(e2, 1e-4);
    EXPECT_GT(std::log2(e1 / e2), 1.8);
  }
}

// The closed form itself: inlet value and zero outlet gradient hold.
TEST(ReferencePlugFlow, ClosedFormMeetsItsBoundaryConditions) {
  const testing::AxialDispersion1D c{100.0, 100.0, 1.462, 100.0, 2.0};
  EXPECT_NEAR(c(0.0), 2.0, 1e-12);
  EXPECT_NEAR((c(100.0) - c(100.0 - 1e-5)) / 1e-5, 0.0, 1e-6);
  const testing::AxialDispersion1D no_dispersion{100.0, 1e-6, 1.462, 100.0, 2.0};
  // docs/benchmark.md, section 5: 0.4635.
  EXPECT_NEAR(no_dispersion(100.0), 2.0 * std::exp(-1.462), 1e-6);
}

}  // namespace
}  // namespace adrsph::reference
