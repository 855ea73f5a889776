// The reference for a reaction network (reference_network.hpp): Newton on the coupled
// species against the single-species solve, the closed forms of A + B -> C in plug flow,
// the discrete mass balances of the reactor, and the product of a nonlinear single-reactant
// law.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "adrsph/reference_network.hpp"
#include "reference/network_system.hpp"

namespace adrsph::reference {
namespace {

Reaction reaction(RateLaw law, double k, std::vector<int> reactants, std::vector<int> products) {
  Reaction r;
  r.law = law;
  r.k = k;
  r.reactants = std::move(reactants);
  r.products = std::move(products);
  return r;
}

double max_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

// Flow-weighted flux of species s through x = L: sum_j u_j dy C_s(nx - 1, j), the outlet
// face carrying the cell value (zero gradient, no diffusive flux).
double outflow(const NetworkSolution& s, const NetworkProblem& p, int sp) {
  const Grid& g = s.grid;
  const std::vector<double> u = detail::cell_average_velocity(p.flow, g);
  double f = 0.0;
  for (int j = 0; j < g.ny; ++j)
    f += u[static_cast<std::size_t>(j)] * g.dy() * s.c[sp][g.index(g.nx - 1, j)];
  return f;
}

// What enters through x = 0: advection u_j dy c_in plus the inlet face's diffusive flux
// 2 D dy (c_in - C_0j) / dx (the half-cell gradient of the scheme).
double inflow(const NetworkSolution& s, const NetworkProblem& p, int sp) {
  const Grid& g = s.grid;
  const std::vector<double> u = detail::cell_average_velocity(p.flow, g);
  const NetworkProblem::Species& q = p.species[static_cast<std::size_t>(sp)];
  double f = 0.0;
  for (int j = 0; j < g.ny; ++j)
    f += u[static_cast<std::size_t>(j)] * g.dy() * q.c_in +
         2.0 * q.D * g.dy() / g.dx() * (q.c_in - s.c[sp][g.index(0, j)]);
  return f;
}

double flow_rate(const NetworkSolution& s, const NetworkProblem& p) {
  const std::vector<double> u = detail::cell_average_velocity(p.flow, s.grid);
  double q = 0.0;
  for (double uj : u) q += uj * s.grid.dy();
  return q;
}

void print_report(const char* what, const SolveReport& r) {
  std::printf("  %s: %d iterations, last change %.1e, residual %.1e, %.3f s + %.3f s (%s)\n", what,
              r.corrections, r.last_change, r.residual, r.assembly_seconds, r.solve_seconds,
              r.solver.c_str());
}

// One species with first-order kinetics: the network is linear, J = A + k V is the
// single-species matrix and Newton is solve_steady's deferred correction, step for step.
TEST(ReferenceNetwork, OneFirstOrderSpeciesIsTheSingleSpeciesSolve) {
  const Case c;  // the reactor: D = 10, species.k = 1.462, c_in = 2
  const NetworkProblem np = network_problem_from_case(c);
  ASSERT_EQ(np.species.size(), 1u);
  ASSERT_EQ(np.reactions.size(), 1u);
  EXPECT_EQ(np.reactions[0].law, RateLaw::first_order);
  EXPECT_EQ(np.reactions[0].k, c.species.k);
  EXPECT_EQ(np.reactions[0].reactants, std::vector<int>{0});
  EXPECT_TRUE(np.reactions[0].products.empty());
  const Problem sp = np.species_problem(0);
  EXPECT_EQ(sp.D, c.species.D);
  EXPECT_EQ(sp.k, 0.0);
  EXPECT_EQ(sp.c_in, c.species.c_in);
  EXPECT_TRUE(sp.reactions.empty());
  EXPECT_EQ(sp.velocity(0.0), c.u_max());

  const Solution single = solve_steady(problem_from_case(c), 200, 20);
  const NetworkSolution net = solve_network_steady(np, 200, 20);
  ASSERT_TRUE(net.report.converged);
  const double d = max_difference(net.c[0], single.c);
  print_report("one species, species.k", net.report);
  std::printf("  max |network - solve_steady| = %.2e (solve_steady: %d corrections)\n", d,
              single.report.corrections);
  EXPECT_LT(d, 1e-10);
  EXPECT_LT(net.report.residual, 1e-10);
  EXPECT_EQ(max_difference(net.species_solution(0).c, net.c[0]), 0.0);

  // A [[reaction]] table with a zone (k x 3 on x in [20, 60), y < 0): the same rule.
  Reaction zoned = reaction(RateLaw::first_order, 1.462, {0}, {});
  zoned.zones = {Reaction::Zone{20.0, 60.0, -5.0, 0.0, 3.0}};
  NetworkProblem nz = np;
  nz.reactions = {zoned};
  Problem pz = problem_from_case(c);
  pz.k = 0.0;
  pz.reactions = {zoned};
  const double dz =
      max_difference(solve_network_steady(nz, 200, 20).c[0], solve_steady(pz, 200, 20).c);
  std::printf("  with a zone: max |network - solve_steady| = %.2e\n", dz);
  EXPECT_LT(dz, 1e-10);
}

// Plug flow u = U, D = 1e-6 (axial dispersion D k A0 / U^2 ~ 1e-10 of the rate: negligible),
// A + B -> C with R = k A B: every row is a batch reactor of age t = x / U,
//   A0 = B0:  A = A0 / (1 + k A0 t)
//   A0 > B0:  A = Delta / (1 - (B0 / A0) e^{-k Delta t}), B = A - Delta, Delta = A0 - B0.
// Away from the outlet the scheme is second order. At the outlet the zero-gradient face
// carries C_P: without an outlet layer (D -> 0) the last cell's balance U (C_P - C_w) = -dx R
// is that of the whole stretch up to x = L, so C_P is the outlet value C(L) (compared with
// it here) to O(dx^2), but the limited slopes of the last faces see that half-cell shift: the
// last three cells carry a first-order error, a fraction of the shift |C'(L)| dx / 2.
struct PlugFlowErrors {
  double a = 0.0, b = 0.0;                // max |C - exact| / exact, cells with x_c < 0.9 L
  double a_outlet = 0.0, b_outlet = 0.0;  // the same over the last three cells
  double shift_a = 0.0, shift_b = 0.0;    // |C'(L)| dx / (2 C(L))
  double balance_a = 0.0;                 // max |A + C - A0| over all cells
  double balance_b = 0.0;                 // max |B + C - B0|
  int iterations = 0;
};

PlugFlowErrors plug_flow_errors(double a0, double b0, double k, int nx) {
  const double U = 100.0;
  NetworkProblem p;
  p.flow.velocity = [U](double) { return U; };
  p.flow.u_bulk = U;
  p.species = {{"A", 1e-6, a0}, {"B", 1e-6, b0}, {"C", 1e-6, 0.0}};
  p.reactions = {reaction(RateLaw::bimolecular, k, {0, 1}, {2})};
  const NetworkSolution s = solve_network_steady(p, nx, 2);
  EXPECT_TRUE(s.report.converged);
  EXPECT_LT(s.report.residual, 1e-10);
  PlugFlowErrors e;
  e.iterations = s.report.corrections;
  const double delta = a0 - b0;
  auto exact_a = [&](double t) {
    return delta == 0.0 ? a0 / (1.0 + k * a0 * t)
                        : delta / (1.0 - (b0 / a0) * std::exp(-k * delta * t));
  };
  for (int i = 0; i < nx; ++i) {
    const bool outlet = i + 3 >= nx;
    const double t = (i + 1 < nx ? s.grid.xc(i) : p.flow.length) / U;
    const double a = exact_a(t), b = a - delta;
    for (int j = 0; j < 2; ++j) {
      const long P = s.grid.index(i, j);
      const double ea = std::abs(s.c[0][P] - a) / a, eb = std::abs(s.c[1][P] - b) / b;
      if (outlet) {
        e.a_outlet = std::max(e.a_outlet, ea);
        e.b_outlet = std::max(e.b_outlet, eb);
      } else if (s.grid.xc(i) < 0.9 * p.flow.length) {
        e.a = std::max(e.a, ea);
        e.b = std::max(e.b, eb);
      }
      e.balance_a = std::max(e.balance_a, std::abs(s.c[0][P] + s.c[2][P] - a0));
      e.balance_b = std::max(e.balance_b, std::abs(s.c[1][P] + s.c[2][P] - b0));
    }
  }
  const double aL = exact_a(p.flow.length / U), bL = aL - delta;  // dA/dx = dB/dx = -k A B / U
  e.shift_a = k * bL / U * s.grid.dx() / 2.0;
  e.shift_b = k * aL / U * s.grid.dx() / 2.0;
  return e;
}

TEST(ReferenceNetwork, PlugFlowBimolecularFollowsTheBatchSolution) {
  // k = 1: A(L) = 2/3 for equal feeds of 2; 1.2254 (B(L) = 0.2254) for A0 = 2, B0 = 1.
  for (const double b0 : {2.0, 1.0}) {
    const PlugFlowErrors e1 = plug_flow_errors(2.0, b0, 1.0, 200);
    const PlugFlowErrors e2 = plug_flow_errors(2.0, b0, 1.0, 400);
    const double order_a = std::log2(e1.a / e2.a), order_b = std::log2(e1.b / e2.b);
    std::printf(
        "  A0 = 2, B0 = %g, x < 0.9 L: A error %.3e (200 cells), %.3e (400), order %.2f; B error "
        "%.3e, %.3e, order %.2f\n",
        b0, e1.a, e2.a, order_a, e1.b, e2.b, order_b);
    std::printf(
        "    last 3 cells: A %.3e, %.3e (%.2f of the half-cell shift), B %.3e, %.3e (%.2f); "
        "|A + C - A0| %.1e, |B + C - B0| %.1e; %d, %d iterations\n",
        e1.a_outlet, e2.a_outlet, e2.a_outlet / e2.shift_a, e1.b_outlet, e2.b_outlet,
        e2.b_outlet / e2.shift_b, std::max(e1.balance_a, e2.balance_a),
        std::max(e1.balance_b, e2.balance_b), e1.iterations, e2.iterations);
    EXPECT_GT(order_a, 1.8);
    EXPECT_GT(order_b, 1.8);
    EXPECT_LT(e2.a, 2e-5);
    EXPECT_LT(e2.b, 2e-5);
    // The outlet cells: first order, measured 0.15 of the shift.
    EXPECT_LT(e2.a_outlet, 0.3 * e2.shift_a);
    EXPECT_LT(e2.b_outlet, 0.3 * e2.shift_b);
    EXPECT_GT(std::log2(e1.a_outlet / e2.a_outlet), 0.9);
    // A + C and B + C obey the reaction-free transport of their inlet values (equal D, and
    // the limited slope is odd in C): constant to round-off and the Newton tolerance.
    EXPECT_LT(std::max(e1.balance_a, e2.balance_a), 1e-10);
    EXPECT_LT(std::max(e1.balance_b, e2.balance_b), 1e-10);
  }
}

// The parabolic reactor (u_max = 200, R = 5, L = 100; D = 10: Pe = u_bulk 2R / D = 100,
// u_bulk L / D = 1000). The scheme is conservative: summed over the cells, the balances (N1)
// telescope to
//   outflow_s = inflow_s - sum_r nu_rs (turnover of r)
// (inflow: advection of c_in,s plus the inlet face's diffusive flux), so any sum of species
// in which the turnovers cancel leaves at the rate it enters.
constexpr int kMaxNewtonIterations = 35;  // measured: 22 (A + B -> C), 27 (A + B -> C -> P)

// A + B -> C (k = 0.5), D_A = D_C = 10, D_B = 20: A + C obeys the reaction-free transport of
// A0 (one D, and the limited slope is odd in C), so it is A0 in every cell, carries no
// diffusive flux through the inlet, and leaves at the rate A enters, Q A0.
TEST(ReferenceNetwork, ParabolicReactorOutflowOfAPlusCIsTheInflowOfA) {
  Case c;
  c.species.D = 10.0;
  NetworkProblem p = network_problem_from_case(c);
  p.species = {{"A", 10.0, 2.0}, {"B", 20.0, 1.5}, {"C", 10.0, 0.0}};
  p.reactions = {reaction(RateLaw::bimolecular, 0.5, {0, 1}, {2})};
  const NetworkSolution s = solve_network_steady(p, 200, 20);
  print_report("A + B -> C", s.report);
  ASSERT_TRUE(s.report.converged);
  EXPECT_LT(s.report.corrections, kMaxNewtonIterations);
  EXPECT_LT(s.report.residual, 1e-10);
  const double q = flow_rate(s, p);
  const double out_a = outflow(s, p, 0), out_b = outflow(s, p, 1), out_c = outflow(s, p, 2);
  const double rel_a = std::abs(out_a + out_c - 2.0 * q) / (2.0 * q);
  const double in_bc = inflow(s, p, 1) + inflow(s, p, 2);
  const double rel_b = std::abs(out_b + out_c - in_bc) / in_bc;
  std::printf(
      "  outlet means A %.6f B %.6f C %.6f; (A + C) out / (Q A0) - 1 = %.1e; (B + C) out / in "
      "- 1 = %.1e, in / (Q B0) - 1 = %.1e (inlet diffusion)\n",
      out_a / q, out_b / q, out_c / q, rel_a, rel_b, in_bc / (1.5 * q) - 1.0);
  EXPECT_LT(rel_a, 1e-8);
  EXPECT_LT(rel_b, 1e-8);
  EXPECT_GT(out_c / q, 0.3);  // a real conversion
}

// The chain A + B -> C (k = 0.5), C -> P (k = 1), D_A = D_C = D_P = 10, D_B = 20, with both
// linear solvers: A + C + P and B + C + P leave at their inflows. (A + C + P is not exactly
// A0 here: the limiter is not linear in the three species; the inlet diffusive flux it then
// carries is part of the inflow.)
TEST(ReferenceNetwork, ParabolicReactorChainConservesMassWithBothSolvers) {
  Case c;
  c.species.D = 10.0;
  NetworkProblem p = network_problem_from_case(c);
  p.species = {{"A", 10.0, 2.0}, {"B", 20.0, 1.5}, {"C", 10.0, 0.0}, {"P", 10.0, 0.0}};
  p.reactions = {reaction(RateLaw::bimolecular, 0.5, {0, 1}, {2}),
                 reaction(RateLaw::first_order, 1.0, {2}, {3})};
  std::vector<std::vector<double>> first;
  for (const LinearSolver ls : {LinearSolver::sparse_lu, LinearSolver::bicgstab_ilut}) {
    SolverOptions opt;
    opt.solver = ls;
    const NetworkSolution s = solve_network_steady(p, 200, 20, opt);
    print_report("A + B -> C -> P", s.report);
    ASSERT_TRUE(s.report.converged);
    EXPECT_LT(s.report.corrections, kMaxNewtonIterations);
    EXPECT_LT(s.report.residual, 1e-10);
    const double q = flow_rate(s, p);
    const double out_a = outflow(s, p, 0), out_b = outflow(s, p, 1);
    const double out_c = outflow(s, p, 2), out_p = outflow(s, p, 3);
    const double in_cp = inflow(s, p, 2) + inflow(s, p, 3);
    const double in_a = inflow(s, p, 0) + in_cp, in_b = inflow(s, p, 1) + in_cp;
    const double rel_a = std::abs(out_a + out_c + out_p - in_a) / in_a;
    const double rel_b = std::abs(out_b + out_c + out_p - in_b) / in_b;
    std::printf(
        "  outlet means A %.6f B %.6f C %.6f P %.6f; (A + C + P) out / in - 1 = %.1e, "
        "(B + C + P) %.1e; (A + C + P) out / (Q A0) - 1 = %.1e\n",
        out_a / q, out_b / q, out_c / q, out_p / q, rel_a, rel_b,
        (out_a + out_c + out_p) / (2.0 * q) - 1.0);
    EXPECT_LT(rel_a, 1e-8);
    EXPECT_LT(rel_b, 1e-8);
    EXPECT_GT(out_c / q, 0.05);  // both reactions ran
    EXPECT_GT(out_p / q, 0.05);
    if (first.empty()) {
      first = s.c;
    } else {
      double d = 0.0;
      for (std::size_t k = 0; k < s.c.size(); ++k)
        d = std::max(d, max_difference(s.c[k], first[k]));
      std::printf("  max |BiCGSTAB - SparseLU| = %.1e\n", d);
      EXPECT_LT(d, 1e-9);
    }
  }
}

// A -> B with one nonlinear law: A matches the single-species solve (slope-bound iteration,
// reaction_terms.cpp) of the same [[reaction]] table, and B is what A lost: B = A0 - A in
// every cell (equal D) and at the outlet.
TEST(ReferenceNetwork, SingleReactantProductIsTheConsumedReactant) {
  Reaction mm = reaction(RateLaw::michaelis_menten, 1.0, {0}, {1});
  mm.km = 0.5;
  Reaction n2 = reaction(RateLaw::nth_order, 0.75, {0}, {1});
  n2.order = 2.0;
  Case c;
  c.species.k = 0.0;
  for (const Reaction& r : {mm, n2}) {
    NetworkProblem p = network_problem_from_case(c);
    p.species = {{"A", 10.0, 2.0}, {"B", 10.0, 0.0}};
    p.reactions = {r};
    const NetworkSolution s = solve_network_steady(p, 200, 20);
    print_report(r.law == RateLaw::nth_order ? "n = 2, A -> B" : "Michaelis-Menten, A -> B",
                 s.report);
    ASSERT_TRUE(s.report.converged);
    EXPECT_LT(s.report.residual, 1e-10);
    Problem single = problem_from_case(c);
    single.reactions = {r};
    const Solution a = solve_steady(single, 200, 20);
    double lost = 0.0;
    for (std::size_t i = 0; i < s.c[0].size(); ++i)
      lost = std::max(lost, std::abs(s.c[0][i] + s.c[1][i] - 2.0));
    const double q = flow_rate(s, p);
    const double out_a = outflow(s, p, 0), out_b = outflow(s, p, 1);
    const double rel = std::abs(out_b - (2.0 * q - out_a)) / (2.0 * q - out_a);
    std::printf(
        "  outlet A %.6f B %.6f: |B_out - consumed| / consumed = %.1e, max |A + B - 2| = %.1e, "
        "max |A - solve_steady| = %.1e (%d corrections)\n",
        out_a / q, out_b / q, rel, lost, max_difference(s.c[0], a.c), a.report.corrections);
    EXPECT_LT(rel, 1e-9);
    EXPECT_LT(lost, 1e-10);
    EXPECT_LT(max_difference(s.c[0], a.c), 1e-9);
    EXPECT_GT(out_b / q, 0.5);  // a real conversion
  }
}

// J of (N2) against central differences of the residual (upwind: F is smooth in U) at a
// positive state, every law and a zone: each reaction derivative, the bimolecular cross terms
// and the products' negative entries; and the Newton iteration it drives converges fast when
// the limiter adds nothing to iterate (first-order upwind: J is F's exact Jacobian).
TEST(ReferenceNetwork, JacobianIsTheDerivativeOfTheResidual) {
  Case c;
  NetworkProblem p = network_problem_from_case(c);
  p.species = {{"A", 10.0, 2.0}, {"B", 5.0, 1.5}, {"C", 20.0, 0.0}, {"P", 10.0, 0.0}};
  Reaction mm = reaction(RateLaw::michaelis_menten, 2.0, {2}, {3});
  mm.km = 0.5;
  Reaction n25 = reaction(RateLaw::nth_order, 0.7, {1}, {3, 0});
  n25.order = 2.5;
  Reaction bi = reaction(RateLaw::bimolecular, 3.0, {0, 1}, {2});
  bi.zones = {Reaction::Zone{0.0, 50.0, -5.0, 5.0, 2.0}};
  p.reactions = {bi, mm, n25, reaction(RateLaw::first_order, 1.5, {3}, {})};
  const Grid g{20, 4, p.flow.length, p.flow.half_width};
  const detail::NetworkSystem sys(p, g);
  const long n = g.cells() * 4;
  Eigen::VectorXd u(n), v(n);
  for (long i = 0; i < n; ++i) {
    u[i] = 0.2 + 1.5 * std::abs(std::sin(0.37 * static_cast<double>(i) + 0.1));
    v[i] = std::cos(1.3 * static_cast<double>(i));
  }
  const detail::SparseMatrix J = sys.jacobian(u);
  const double eps = 1e-6;
  const Eigen::VectorXd fd =
      (sys.residual(u + eps * v, Limiter::upwind) - sys.residual(u - eps * v, Limiter::upwind)) /
      (2.0 * eps);
  const Eigen::VectorXd jv = J * v;
  // The reaction part alone (J less the transport of the network without reactions), the
  // scale of the check.
  NetworkProblem transport_only = p;
  transport_only.reactions.clear();
  const Eigen::VectorXd jr = jv - detail::NetworkSystem(transport_only, g).jacobian(u) * v;
  const double err = (jv - fd).cwiseAbs().maxCoeff() / jr.cwiseAbs().maxCoeff();
  std::printf("  max |J v - FD| / max |J_reaction v| = %.1e\n", err);
  EXPECT_LT(err, 1e-7);

  SolverOptions opt;
  opt.limiter = Limiter::upwind;
  const NetworkSolution s = solve_network_steady(p, 100, 10, opt);
  print_report("four laws, upwind", s.report);
  ASSERT_TRUE(s.report.converged);
  EXPECT_LE(s.report.corrections, 15);  // measured: 11
  EXPECT_LT(s.report.residual, 1e-11);
}

TEST(ReferenceNetwork, RefusesWhatItCannotSolve) {
  auto message = [](const Case& c) -> std::string {
    try {
      network_problem_from_case(c);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  Case c;
  c.more_species.push_back(c.species);
  c.more_species.back().name = "B";
  Reaction half = reaction(RateLaw::nth_order, 1.0, {0}, {1});
  half.order = 0.5;
  c.reactions = {reaction(RateLaw::first_order, 1.0, {0}, {1}), half};
  EXPECT_NE(message(c).find("reaction[1]"), std::string::npos) << message(c);
  Reaction mm = reaction(RateLaw::michaelis_menten, 1.0, {0}, {});
  c.reactions = {mm};
  EXPECT_NE(message(c).find("reaction[0]"), std::string::npos) << message(c);
  c.reactions = {reaction(RateLaw::bimolecular, 1.0, {1, 1}, {})};
  EXPECT_NE(message(c).find("reaction[0]: bimolecular"), std::string::npos) << message(c);
  c.reactions = {reaction(RateLaw::first_order, 1.0, {0}, {2})};
  EXPECT_NE(message(c).find("product index 2"), std::string::npos) << message(c);
  c.reactions = {reaction(RateLaw::bimolecular, 1.0, {0, 1}, {})};
  EXPECT_EQ(message(c), "");
  const NetworkProblem p = network_problem_from_case(c);
  EXPECT_EQ(p.species.size(), 2u);
  EXPECT_EQ(p.species[1].name, "B");
  EXPECT_EQ(p.reactions.size(), 2u);  // the table and species.k, appended
  EXPECT_EQ(p.reactions[1].law, RateLaw::first_order);
  EXPECT_THROW(solve_network_steady(p, 1, 4), std::invalid_argument);
}

}  // namespace
}  // namespace adrsph::reference
