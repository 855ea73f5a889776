// Reference solver, assembly check by a manufactured solution (issue 4; docs/benchmark.md,
// section 5):
// C = (2 + cos(pi x / L)) (1 + 0.3 cos(pi y / R)) satisfies the zero-gradient walls and
// outlet; its source term makes it exact. The error must fall at the designed order (2)
// for the full operator with the van Leer limiter, and at order 1 for plain upwind.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "adrsph/reference.hpp"

namespace adrsph::reference {
namespace {

constexpr double kPi = std::numbers::pi;

Problem manufactured_problem(double D) {
  Problem p;
  p.length = 100.0;
  p.half_width = 5.0;
  p.D = D;
  p.k = 1.462;
  p.velocity = parabolic_profile(200.0, 5.0);
  const double L = p.length, R = p.half_width, k = p.k;
  auto f = [L](double x) { return 2.0 + std::cos(kPi * x / L); };
  auto g = [R](double y) { return 1.0 + 0.3 * std::cos(kPi * y / R); };
  p.inlet = [f, g](double y) { return f(0.0) * g(y); };
  const auto u = p.velocity;
  p.source = [=](double x, double y) {
    const double c_x = -(kPi / L) * std::sin(kPi * x / L) * g(y);
    const double c_xx = -(kPi / L) * (kPi / L) * std::cos(kPi * x / L) * g(y);
    const double c_yy = -f(x) * 0.3 * (kPi / R) * (kPi / R) * std::cos(kPi * y / R);
    return u(y) * c_x - D * (c_xx + c_yy) + k * f(x) * g(y);
  };
  return p;
}

double exact(const Problem& p, double x, double y) {
  return (2.0 + std::cos(kPi * x / p.length)) * (1.0 + 0.3 * std::cos(kPi * y / p.half_width));
}

// Root-mean-square error of the cell values against C_exact at the cell centres.
double rms_error(const Problem& p, int nx, int ny, Limiter limiter) {
  SolverOptions opt;
  opt.limiter = limiter;
  // minmod's deferred correction contracts slowly (0.97..0.99 per sweep where it takes the
  // downwind difference); 1e-8 is far below the discretisation errors measured here.
  if (limiter == Limiter::minmod) {
    opt.tolerance = 1e-8;
    opt.max_corrections = 3000;
  }
  const Solution s = solve_steady(p, nx, ny, opt);
  EXPECT_TRUE(s.report.converged);
  double sum = 0.0;
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j) {
      const double e = s.at(i, j) - exact(p, s.grid.xc(i), s.grid.yc(j));
      sum += e * e;
    }
  return std::sqrt(sum / (static_cast<double>(nx) * ny));
}

std::vector<double> observed_orders(double D, Limiter limiter) {
  const Problem p = manufactured_problem(D);
  std::vector<double> err;
  for (int nx : {50, 100, 200, 400}) err.push_back(rms_error(p, nx, nx / 5, limiter));
  std::vector<double> orders;
  for (std::size_t l = 1; l < err.size(); ++l) {
    orders.push_back(std::log2(err[l - 1] / err[l]));
    std::printf("  D=%g %s: rms error %.3e -> %.3e, order %.3f\n", D, to_string(limiter),
                err[l - 1], err[l], orders.back());
  }
  return orders;
}

// Advection dominated (cell Peclet u dx / D up to 400): the limiter decides the order.
TEST(ReferenceManufactured, VanLeerIsSecondOrderWhenAdvectionDominates) {
  for (double order : observed_orders(1.0, Limiter::van_leer)) EXPECT_GT(order, 1.8);
}

// Diffusion dominated: the central diffusion and the Dirichlet inlet decide it.
TEST(ReferenceManufactured, VanLeerIsSecondOrderWhenDiffusionDominates) {
  for (double order : observed_orders(100.0, Limiter::van_leer)) EXPECT_GT(order, 1.8);
}

TEST(ReferenceManufactured, MinmodIsSecondOrderToo) {
  const std::vector<double> orders = observed_orders(1.0, Limiter::minmod);
  EXPECT_GT(orders.back(), 1.8);
}

// The test can tell: first-order upwind falls at order 1.
TEST(ReferenceManufactured, PlainUpwindIsFirstOrder) {
  const std::vector<double> orders = observed_orders(1.0, Limiter::upwind);
  EXPECT_LT(orders.back(), 1.3);
  EXPECT_GT(orders.back(), 0.8);
}

}  // namespace
}  // namespace adrsph::reference
