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

namespace adrsph::reference {
namespace {

// Nonlinear kinetics ([[reaction]] tables, reaction_terms.cpp) in plug flow without
// dispersion: every row is a batch reactor of age x / U, C(x) = B(x / U), with
// B = c_in / (1 + k c_in t) for R = k C^2 and km ln(B / c_in) + B - c_in = -k t for
// Michaelis-Menten (solved by bisection here). The error must fall at least as dx (van Leer
// advection, second order where smooth; the steady reaction terms are cell-centred).
double batch_mm(double c_in, double k, double km, double t) {
  double lo = 0.0, hi = c_in;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (km * std::log(mid / c_in) + mid - c_in + k * t > 0.0 ? hi : lo) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(ReferenceKinetics, PlugFlowFollowsTheBatchSolutions) {
  const double U = 100.0;
  for (const Reaction& r : {Reaction::of(RateLaw::nth_order, 0.75, 2.0, 0.0, {}),
                            Reaction::of(RateLaw::michaelis_menten, 1.0, 1.0, 0.5, {})}) {
    std::vector<double> errors;
    for (const int nx : {400, 800}) {
      Problem p;
      p.D = 0.0;
      p.k = 0.0;
      p.reactions = {r};
      p.velocity = [U](double) { return U; };
      const Solution s = solve_steady(p, nx, 2);
      EXPECT_TRUE(s.report.converged) << to_string(r.law);
      EXPECT_LT(s.report.residual, 1e-9) << to_string(r.law);
      double err = 0.0;
      for (int i = 0; i < nx; ++i) {
        const double t = s.grid.xc(i) / U;
        const double exact = r.law == RateLaw::nth_order ? p.c_in / (1.0 + r.k * p.c_in * t)
                                                         : batch_mm(p.c_in, r.k, r.km, t);
        err = std::max(err, std::abs(s.at(i, 0) - exact) / exact);
      }
      errors.push_back(err);
    }
    std::printf("  plug flow, %s: max rel. error %.3e (400 cells), %.3e (800), order %.2f\n",
                to_string(r.law), errors[0], errors[1], std::log2(errors[0] / errors[1]));
    EXPECT_LT(errors[1], 2e-3) << to_string(r.law);
    EXPECT_GT(std::log2(errors[0] / errors[1]), 0.9) << to_string(r.law);
  }
}

// A first-order [[reaction]] table is species.k by another name: the same solution.
TEST(ReferenceKinetics, FirstOrderTableEqualsSpeciesK) {
  Problem with_k;
  with_k.velocity = parabolic_profile(200.0, 5.0);
  Problem with_table = with_k;
  with_table.k = 0.0;
  with_table.reactions = {Reaction::of(RateLaw::first_order, with_k.k, 1.0, 0.0, {})};
  const Solution a = solve_steady(with_k, 200, 20), b = solve_steady(with_table, 200, 20);
  double diff = 0.0;
  for (std::size_t i = 0; i < a.c.size(); ++i) diff = std::max(diff, std::abs(a.c[i] - b.c[i]));
  EXPECT_LT(diff, 1e-10);
}

// Problems the reference cannot take are refused with the reaction named.
TEST(ReferenceKinetics, UnboundedSlopesAreRefused) {
  Case c;
  c.reactions = {Reaction::of(RateLaw::nth_order, 1.0, 0.5, 0.0, {})};
  try {
    problem_from_case(c);
    FAIL() << "accepted n = 0.5";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("reaction[0]"), std::string::npos) << e.what();
  }
  c.reactions = {Reaction::of(RateLaw::michaelis_menten, 1.0, 1.0, 0.5, {})};
  EXPECT_NO_THROW(problem_from_case(c));
}

}  // namespace
}  // namespace adrsph::reference
