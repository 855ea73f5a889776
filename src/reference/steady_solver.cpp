// Steady solve (docs/benchmark.md, section 5): first-order upwind matrix A (an M-matrix)
// factorised or preconditioned once; the limited high-order advective flux is iterated by deferred
// correction, A C^{n+1} = b - corr(C^n), until C stops changing. At convergence C solves
// the full second-order TVD scheme; `residual` measures that directly.
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "reference/finite_volume.hpp"

namespace adrsph::reference {
namespace {

using Clock = std::chrono::steady_clock;
using detail::seconds_since;

}  // namespace

Solution solve_steady(const Problem& p, int nx, int ny, const SolverOptions& opt) {
  if (nx < 2 || ny < 1) throw std::invalid_argument("reference: need nx >= 2 and ny >= 1");
  if (!p.velocity) throw std::invalid_argument("reference: no velocity profile");
  if (!(p.D >= 0.0) || !(p.k >= 0.0) || !(p.length > 0.0) || !(p.half_width > 0.0))
    throw std::invalid_argument("reference: need D >= 0, k >= 0, L > 0, R > 0");

  Solution s;
  s.grid = Grid{nx, ny, p.length, p.half_width};
  const Grid& g = s.grid;
  SolveReport& rep = s.report;
  rep.solver =
      std::string(to_string(opt.solver)) + " + " + to_string(opt.limiter) + " deferred correction";

  auto t0 = Clock::now();
  const std::vector<double> u_cell = detail::cell_average_velocity(p, g);
  const detail::UpwindSystem sys = detail::assemble_upwind_system(p, g, u_cell);
  rep.assembly_seconds = seconds_since(t0);

  t0 = Clock::now();
  auto solver = detail::make_upwind_solver(opt.solver, sys.A);
  Eigen::VectorXd c = solver->solve(sys.b, Eigen::VectorXd::Zero(g.cells()));
  Eigen::VectorXd corr(g.cells());
  double scale = std::max(std::abs(p.c_in), c.cwiseAbs().maxCoeff());
  if (scale == 0.0) scale = 1.0;
  // Nothing to iterate for upwind advection and linear kinetics.
  rep.converged = opt.limiter == Limiter::upwind && p.reactions.empty();
  // Under-relaxation, halved whenever the change has not improved for 10 iterations: the
  // limiter's switches (minmod's kinks) can otherwise leave a limit cycle near 1e-10.
  detail::StallRelaxation relaxation;
  for (int it = 1; !rep.converged && it <= opt.max_corrections; ++it) {
    detail::advective_correction(p, g, u_cell, opt.limiter, c, corr);
    detail::add_reaction_correction(p, g, c, corr);
    const Eigen::VectorXd next = solver->solve(sys.b - corr, c);
    const double change = (next - c).cwiseAbs().maxCoeff() / scale;
    c += relaxation.relax * (next - c);
    rep.last_change = change;
    rep.corrections = it;
    rep.converged = change < opt.tolerance;
    relaxation.update(change);
  }
  rep.relaxation = relaxation.relax;
  rep.solve_seconds = seconds_since(t0);

  detail::advective_correction(p, g, u_cell, opt.limiter, c, corr);
  detail::add_reaction_correction(p, g, c, corr);
  const double bnorm = sys.b.norm();
  rep.residual = (sys.A * c + corr - sys.b).norm() / (bnorm > 0.0 ? bnorm : 1.0);

  s.c.assign(c.data(), c.data() + c.size());
  return s;
}

}  // namespace adrsph::reference
