// Steady solve of a reaction network (reference_network.hpp, network_system.hpp): Newton's
// method on (N1), F(U) = 0, with the Jacobian (N2) of the first-order upwind transport and
// the exact reaction derivatives,
//   J(U^m) dU = -F(U^m),   U^{m+1} = U^m + w dU                                       (N3)
// from U^0 = 0. F holds the full limited advective flux, J only its upwind part: the limiter
// is iterated by deferred correction inside the same loop, as in the single-species solve
// (steady_solver.cpp), and at convergence U solves the full second-order TVD scheme with the
// reactions (`residual` measures that directly). For a linear network (first-order laws
// only) J is constant and (N3) is exactly the deferred correction of solve_steady.
//
// Factorisation. Newton converges quadratically in the reactions but only linearly in the
// lagged limiter, so a fresh J pays only while the reaction linearisation is poor, and a
// factorisation costs far more than an iteration (800x80 cells, 3 species, SparseLU: ~8 s
// against ~0.3 s for a residual and a back-substitution). J is refactorised at every
// iteration while max |dU| > 0.1 C_scale (kNewtonPhase); after that it is kept (a chord
// iteration), and refactorised once more whenever the change stops decreasing. Measured on
// the reactor (200x20, D = 10, A + B -> C (+ C -> P), Michaelis-Menten A -> B, k = 0.5 .. 50):
// the same iteration counts as refactorising at every iteration (24 .. 74, set by the
// limiter's deferred correction) with 3 to 5 factorisations instead of 24 .. 74; never
// refactorising after the first two costs up to 2.4x the iterations and needed
// under-relaxation once. A linear network (first-order laws only) is factorised once. The
// first step, from U = 0 where every law but first order has zero slope, is the
// reaction-free transport of the feeds (plus first-order decay).
//
// Stop when max |dU| / C_scale < opt.tolerance, C_scale = the largest inlet value of all
// species (1 if all are 0). If the change has not improved for 10 iterations the step is
// under-relaxed by halves (down to w = 1/16), as in steady_solver.cpp.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "reference/network_system.hpp"

namespace adrsph::reference {
namespace {

using Clock = std::chrono::steady_clock;
using detail::seconds_since;

// Refactorise J at every iteration while the change exceeds this (relative to C_scale).
constexpr double kNewtonPhase = 0.1;

}  // namespace

NetworkSolution solve_network_steady(const NetworkProblem& p, int nx, int ny,
                                     const SolverOptions& opt) {
  if (nx < 2 || ny < 1) throw std::invalid_argument("reference: need nx >= 2 and ny >= 1");
  if (!p.flow.velocity) throw std::invalid_argument("reference: no velocity profile");
  if (!(p.flow.length > 0.0) || !(p.flow.half_width > 0.0))
    throw std::invalid_argument("reference: need L > 0, R > 0");
  detail::check_network(p);

  NetworkSolution out;
  out.grid = Grid{nx, ny, p.flow.length, p.flow.half_width};
  const Grid& g = out.grid;
  SolveReport& rep = out.report;

  auto t0 = Clock::now();
  const detail::NetworkSystem sys(p, g);
  rep.assembly_seconds = seconds_since(t0);

  t0 = Clock::now();
  const int n = sys.species();
  const long unknowns = g.cells() * n;
  double scale = 0.0;
  for (const NetworkProblem::Species& s : p.species) scale = std::max(scale, std::abs(s.c_in));
  if (scale == 0.0) scale = 1.0;

  Eigen::VectorXd u = Eigen::VectorXd::Zero(unknowns);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(unknowns);
  detail::SparseMatrix J;
  std::unique_ptr<detail::UpwindSolver> solver;  // holds a reference to J (BiCGSTAB)
  bool refactor = true;
  int factorisations = 0;
  detail::StallRelaxation relaxation;
  double previous = std::numeric_limits<double>::infinity();
  for (int it = 1; !rep.converged && it <= opt.max_corrections; ++it) {
    const Eigen::VectorXd f = sys.residual(u, opt.limiter);
    const bool fresh = refactor;
    if (refactor) {
      solver.reset();
      J = sys.jacobian(u);
      solver = detail::make_upwind_solver(opt.solver, J);
      ++factorisations;
    }
    const Eigen::VectorXd du = solver->solve(-f, zero);
    const double change = du.cwiseAbs().maxCoeff() / scale;
    if (!std::isfinite(change)) break;  // not converged; the report says so
    u += relaxation.relax * du;
    rep.last_change = change;
    rep.corrections = it;
    rep.converged = change < opt.tolerance;
    refactor =
        !sys.kinetics().linear() && (change > kNewtonPhase || (!fresh && change >= previous));
    previous = change;
    relaxation.update(change);
  }
  rep.relaxation = relaxation.relax;
  rep.solve_seconds = seconds_since(t0);
  rep.solver = std::string(to_string(opt.solver)) + " + " + to_string(opt.limiter) +
               " deferred correction, Newton (" + std::to_string(factorisations) +
               (factorisations == 1 ? " factorisation)" : " factorisations)");

  const double bnorm = sys.b().norm();
  rep.residual = sys.residual(u, opt.limiter).norm() / (bnorm > 0.0 ? bnorm : 1.0);

  out.c.resize(static_cast<std::size_t>(n));
  for (int s = 0; s < n; ++s) {
    const Eigen::VectorXd c = sys.species_field(u, s);
    out.c[static_cast<std::size_t>(s)].assign(c.data(), c.data() + c.size());
  }
  return out;
}

}  // namespace adrsph::reference
