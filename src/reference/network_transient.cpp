// Transient solve of a reaction network (reference_network_transient.hpp). Every cell balance
// (N1) of the steady network (network_system.hpp) gains the storage term V dC_s/dt; BDF2 at a
// constant step dt, the feeds entering through the inlet values f_s of each step:
//   G(U) = V (3 U - 4 U^n + U^{n-1}) / (2 dt) + F(U; f^{n+1}) = 0                    (NT1)
// (implicit Euler, V (U - U^n) / dt, for a first step that does not start at rest). A
// Newton-type (chord) iteration on (NT1) with the Jacobian of the upwind transport and the
// exact reaction slopes taken at an earlier iterate U*,
//   (3V / (2 dt) I + J(U*)) dU = -G(U^m),   U^{m+1} = U^m + w dU                      (NT2)
// from U^0 = 2 U^n - U^{n-1}, the limiter lagged inside the same loop as in the steady solve
// (network_solver.cpp), until max |dU| < tolerance C_scale (w = 1, halved when the change
// stalls, as in the steady solve); then U^{n+1} solves (NT1) with the full limited scheme and
// the reactions.
//
// Factorisation. The storage term dominates the step matrix at the steps the outlet series
// needs (3V / (2 dt) against the reaction slopes V dR/dC), so a matrix factorised at an
// earlier iterate, even of an earlier step, still contracts fast, and so does one that
// leaves out the reaction coupling between species. (NT2) is therefore solved species by
// species with the diagonal blocks M_ss = 3V / (2 dt) + A_s + V dR_s/dC_s of the step matrix,
// a chord iteration whose fixed point is still (NT1): the blocks cost what n one-species
// matrices cost, where the whole matrix has n times the unknowns and n times the band
// (measured, 200 x 20, 3 species: 24 ms an iteration whole, about a fifth of that by blocks).
// J(U*) is refreshed only when an iteration contracts by less than kRefreshContraction or a
// step has needed kRefreshSweeps iterations; a step that the blocks have not settled in
// kCoupledAfterSweeps iterations (a reaction stiff against the storage term) finishes on the
// whole matrix. A linear network (first-order laws) has a constant J: factorised once per
// storage coefficient (the Euler start and BDF2). The iteration count itself is set by the
// lagged limiter, as in the one-species mode (about 9 per step at a Courant number of 0.4).
//
// Feeds, start and windows as in the single-species mode (transient_solver.cpp): f_s of step n
// is species s's feed mean over [t_n - dt/2, t_n + dt/2], and a channel at rest before t = 0
// (every c_init,s equal to its feed's C_in,s(0-) and no reaction running at those values)
// starts with BDF2 and a first window from 0 that carries the feed of [0, dt/2].
#include "adrsph/reference_network_transient.hpp"

#include <Eigen/Sparse>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

#include "reference/network_system.hpp"
#include "species/feed_integral.hpp"
#include "species/inlet_feed.hpp"

namespace adrsph::reference {
namespace {

using detail::SparseMatrix;
using Clock = std::chrono::steady_clock;
using detail::seconds_since;

// Refresh J(U*) when max |dU| of an iteration is more than this fraction of the previous one's.
constexpr double kRefreshContraction = 0.9;
// ... or when a step has taken this many iterations.
constexpr int kRefreshSweeps = 20;
// Segregated species blocks for a step until it has taken this many iterations; then the
// coupled matrix (a reaction stiff against the storage term, V dR/dC ~ V / dt).
constexpr int kCoupledAfterSweeps = 40;

void check(const NetworkTransientProblem& p, int nx, int ny, const TransientOptions& opt) {
  if (nx < 2 || ny < 1) throw std::invalid_argument("reference: need nx >= 2 and ny >= 1");
  if (!p.space.flow.velocity) throw std::invalid_argument("reference: no velocity profile");
  if (!(p.space.flow.length > 0.0) || !(p.space.flow.half_width > 0.0))
    throw std::invalid_argument("reference: need L > 0, R > 0");
  detail::check_network(p.space);
  if (p.feeds.size() != p.space.species.size())
    throw std::invalid_argument("reference: one feed per species needed (" +
                                std::to_string(p.space.species.size()) + " species, " +
                                std::to_string(p.feeds.size()) + " feeds)");
  for (std::size_t s = 0; s < p.feeds.size(); ++s)
    if (!p.feeds[s].inlet_integral)
      throw std::invalid_argument("reference: species[" + std::to_string(s) + "] has no feed");
  detail::check_time_stepping(opt.dt, p.sample_interval, p.t_end);
}

// The step matrix M = alpha V / dt I + J(U*) of (NT2), factorised either whole (coupled) or as
// its species blocks M_ss (segregated: the reaction coupling between species left out of
// the matrix, which then costs what n one-species matrices cost instead of one with n times
// the unknowns and n times the band).
class StepSolver {
 public:
  bool ready() const { return coupled_ ? coupled_solver_ != nullptr : !blocks_.empty(); }
  double storage() const { return storage_; }
  bool coupled() const { return coupled_; }

  void refresh(const detail::NetworkSystem& sys, const Eigen::VectorXd& u, double alpha_v_dt,
               LinearSolver kind, bool coupled) {
    coupled_solver_.reset();
    block_solvers_.clear();
    blocks_.clear();
    coupled_ = coupled;
    storage_ = alpha_v_dt;
    SparseMatrix m = sys.jacobian(u);
    for (Eigen::Index k = 0; k < m.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(m, k); it; ++it)
        if (it.row() == it.col()) it.valueRef() += alpha_v_dt;
    if (coupled) {
      matrix_ = std::move(m);
      coupled_solver_ = detail::make_upwind_solver(kind, matrix_);
      return;
    }
    const int n = sys.species();
    std::vector<std::vector<Eigen::Triplet<double>>> t(static_cast<std::size_t>(n));
    for (Eigen::Index k = 0; k < m.outerSize(); ++k)
      for (SparseMatrix::InnerIterator it(m, k); it; ++it) {
        const long r = it.row(), c = it.col();
        if (r % n == c % n)
          t[static_cast<std::size_t>(r % n)].emplace_back(static_cast<int>(r / n),
                                                          static_cast<int>(c / n), it.value());
      }
    const long cells = sys.grid().cells();
    blocks_.resize(static_cast<std::size_t>(n));
    for (int s = 0; s < n; ++s) {
      SparseMatrix& b = blocks_[static_cast<std::size_t>(s)];
      b.resize(cells, cells);
      b.setFromTriplets(t[static_cast<std::size_t>(s)].begin(),
                        t[static_cast<std::size_t>(s)].end());
      b.makeCompressed();
    }
    for (int s = 0; s < n; ++s)
      block_solvers_.push_back(
          detail::make_upwind_solver(kind, blocks_[static_cast<std::size_t>(s)]));
  }

  // dU = M^{-1} r (coupled) or, species by species, M_ss^{-1} r_s (segregated).
  Eigen::VectorXd solve(const Eigen::VectorXd& r, int n) {
    if (coupled_) return coupled_solver_->solve(r, Eigen::VectorXd::Zero(r.size()));
    const long cells = r.size() / n;
    Eigen::VectorXd du(r.size()), rs(cells);
    for (int s = 0; s < n; ++s) {
      for (long P = 0; P < cells; ++P) rs[P] = r[P * n + s];
      const Eigen::VectorXd d =
          block_solvers_[static_cast<std::size_t>(s)]->solve(rs, Eigen::VectorXd::Zero(cells));
      for (long P = 0; P < cells; ++P) du[P * n + s] = d[P];
    }
    return du;
  }

 private:
  bool coupled_ = false;
  double storage_ = 0.0;
  // The solvers hold references to their matrices (BiCGSTAB): declared after them, so that
  // they are destroyed first.
  SparseMatrix matrix_;
  std::vector<SparseMatrix> blocks_;
  std::unique_ptr<detail::UpwindSolver> coupled_solver_;
  std::vector<std::unique_ptr<detail::UpwindSolver>> block_solvers_;
};

// Rates through the boundaries of species s at inlet value f (the steady fluxes of
// finite_volume.hpp: inlet advection and half-cell diffusion, outlet advection of the last
// cells), its amount held and its net consumption, per unit depth.
struct SpeciesRates {
  double inflow = 0.0, outflow = 0.0, consumed = 0.0, held = 0.0;
};

SpeciesRates species_rates(const detail::NetworkSystem& sys, const Eigen::VectorXd& u,
                           const Eigen::VectorXd& rates, int s, double f) {
  const Grid& g = sys.grid();
  const int n = sys.species();
  const std::vector<double>& u_cell = sys.cell_velocity();
  const double dy = g.dy(), gx = sys.species_problem(s).D * dy / g.dx();
  SpeciesRates r;
  for (int j = 0; j < g.ny; ++j) {
    r.inflow += u_cell[j] * dy * f + 2.0 * gx * (f - u[g.index(0, j) * n + s]);
    r.outflow += u_cell[j] * dy * u[g.index(g.nx - 1, j) * n + s];
  }
  for (long P = 0; P < g.cells(); ++P) {
    r.held += u[P * n + s];
    r.consumed += rates[P * n + s];
  }
  r.held *= sys.cell_volume();
  return r;
}

OutletRow outlet_of(const detail::NetworkSystem& sys, const Eigen::VectorXd& u, int s, double t) {
  const Grid& g = sys.grid();
  const int n = sys.species();
  double flux = 0.0, flow = 0.0, sum = 0.0;
  for (int j = 0; j < g.ny; ++j) {
    const double c = u[g.index(g.nx - 1, j) * n + s], q = sys.cell_velocity()[j] * g.dy();
    flux += q * c;
    flow += q;
    sum += c;
  }
  return {t, flux / flow, sum / g.ny};
}

}  // namespace

NetworkTransientProblem network_transient_problem_from_case(const Case& c) {
  NetworkTransientProblem p;
  p.space = network_problem_from_case(c);
  for (int s = 0; s < c.species_count(); ++s) {
    const Case::Species sp = c.species_at(s);
    NetworkTransientProblem::Feed f;
    f.c_init = sp.c_init;
    f.inlet_integral = [sp](double a, double b) { return feed_integral(sp, a, b); };
    f.before_start = inlet_concentration(sp, -std::numeric_limits<double>::min());
    p.feeds.push_back(std::move(f));
  }
  p.t_end = c.time.t_end;
  p.sample_interval = c.output.outlet_interval;
  return p;
}

NetworkTransientSolution solve_network_transient(const NetworkTransientProblem& p, int nx, int ny,
                                                 const TransientOptions& opt) {
  check(p, nx, ny, opt);
  NetworkTransientSolution out;
  TransientReport& rep = out.report;
  out.final.grid = Grid{nx, ny, p.space.flow.length, p.space.flow.half_width};
  const Grid& g = out.final.grid;
  const double dt = step_dividing(opt.dt, p.sample_interval);
  const long per_sample = std::lround(p.sample_interval / dt);
  const long steps =
      per_sample * static_cast<long>(std::ceil(p.t_end / p.sample_interval * (1.0 - 1e-12)));
  rep.dt = dt;

  auto t0 = Clock::now();
  const detail::NetworkSystem sys(p.space, g);
  rep.assembly_seconds = seconds_since(t0);
  const int n = sys.species();
  const long cells = g.cells(), unknowns = cells * n;
  const double vol = sys.cell_volume();
  const bool linear = sys.kinetics().linear();

  t0 = Clock::now();
  Eigen::VectorXd now(unknowns);
  std::vector<double> rest(static_cast<std::size_t>(n)), f(static_cast<std::size_t>(n));
  double scale = 0.0;
  for (int s = 0; s < n; ++s) {
    const auto& feed = p.feeds[static_cast<std::size_t>(s)];
    rest[static_cast<std::size_t>(s)] = feed.before_start;
    scale = std::max({scale, std::abs(feed.c_init), std::abs(feed.before_start)});
    for (long P = 0; P < cells; ++P) now[P * n + s] = feed.c_init;
  }
  // At rest: each species at its inlet's value and no reaction running there.
  Eigen::VectorXd rates = Eigen::VectorXd::Zero(unknowns);
  sys.kinetics().add_rates(now, rates);
  rep.started_at_rest = rates.cwiseAbs().maxCoeff() == 0.0;
  for (int s = 0; s < n; ++s)
    rep.started_at_rest = rep.started_at_rest && p.feeds[static_cast<std::size_t>(s)].c_init ==
                                                     rest[static_cast<std::size_t>(s)];

  out.balance.assign(static_cast<std::size_t>(n), TransientBalance{});
  double flow_rate = 0.0;
  for (double u : sys.cell_velocity()) flow_rate += u * g.dy();
  out.outlet.assign(static_cast<std::size_t>(n), {});
  for (int s = 0; s < n; ++s) {
    TransientBalance& b = out.balance[static_cast<std::size_t>(s)];
    b.flow_rate = flow_rate;
    b.held_initial = b.held_final =
        species_rates(sys, now, rates, s, rest[static_cast<std::size_t>(s)]).held / flow_rate;
    out.outlet[static_cast<std::size_t>(s)].push_back(outlet_of(sys, now, s, 0.0));
  }

  Eigen::VectorXd before = now, u(unknowns);
  StepSolver step;
  double factor_seconds = 0.0;
  for (long k = 1; k <= steps; ++k) {
    const double t = dt * static_cast<double>(k);
    const bool implicit_euler = k == 1 && !rep.started_at_rest;
    const double lo = k == 1 && rep.started_at_rest ? 0.0 : t - 0.5 * dt, hi = t + 0.5 * dt;
    for (int s = 0; s < n; ++s) {
      const std::size_t si = static_cast<std::size_t>(s);
      f[si] = (p.feeds[si].inlet_integral(lo, hi) - rest[si] * (hi - lo - dt)) / dt;
      scale = std::max(scale, std::abs(f[si]));
    }
    const double alpha_v_dt = (implicit_euler ? 1.0 : 1.5) * vol / dt;
    const Eigen::VectorXd history = implicit_euler
                                        ? Eigen::VectorXd(vol / dt * now)
                                        : Eigen::VectorXd(vol / (2.0 * dt) * (4.0 * now - before));
    u = k == 1 ? now : Eigen::VectorXd(2.0 * now - before);
    const double c_scale = scale > 0.0 ? scale : 1.0;
    const bool exact = opt.limiter == Limiter::upwind && linear;
    bool done = false, fresh = false;
    double change = 0.0, previous = std::numeric_limits<double>::infinity();
    int sweeps = 0;
    // Segregated blocks first; the coupled matrix for the rest of a step they do not settle.
    bool coupled = n == 1;
    detail::StallRelaxation relaxation;  // halves the update when the change stalls
    while (!done && sweeps < opt.max_corrections) {
      const bool stale = !fresh && !linear &&
                         (change > kRefreshContraction * previous || sweeps == kRefreshSweeps);
      const bool escalate = !coupled && sweeps == kCoupledAfterSweeps;
      coupled = coupled || escalate;
      if (!step.ready() || step.storage() != alpha_v_dt || step.coupled() != coupled ||
          (sweeps > 0 && stale)) {
        const auto tf = Clock::now();
        step.refresh(sys, u, alpha_v_dt, opt.solver, coupled);
        factor_seconds += seconds_since(tf);
        ++out.factorisations;
        fresh = true;
      } else {
        fresh = false;
      }
      const Eigen::VectorXd G = alpha_v_dt * u - history + sys.residual(u, opt.limiter, f);
      const Eigen::VectorXd du = step.solve(-G, n);
      previous = sweeps == 0 ? std::numeric_limits<double>::infinity() : change;
      change = du.cwiseAbs().maxCoeff() / c_scale;
      if (!std::isfinite(change)) break;  // not converged; the report says so
      u += relaxation.relax * du;
      relaxation.update(change);
      ++sweeps;
      // One solve of the whole matrix is exact for upwind advection and linear kinetics (the
      // species blocks leave the coupling out: they iterate).
      done = (exact && coupled) || change < opt.tolerance;
    }
    if (coupled && n > 1) ++out.coupled_steps;
    rep.corrections += sweeps;
    rep.max_step_corrections = std::max(rep.max_step_corrections, sweeps);
    rep.worst_change = std::max(rep.worst_change, exact ? 0.0 : change);
    rep.converged = rep.converged && done;
    before = now;
    now = u;

    rates.setZero();
    sys.kinetics().add_rates(now, rates);
    for (int s = 0; s < n; ++s) {
      const std::size_t si = static_cast<std::size_t>(s);
      const SpeciesRates r = species_rates(sys, now, rates, s, f[si]);
      TransientBalance& b = out.balance[si];
      b.inflow += dt * r.inflow / flow_rate;
      b.outflow += dt * r.outflow / flow_rate;
      b.reacted += dt * r.consumed / flow_rate;
      b.held_final = r.held / flow_rate;
    }
    rep.steps = k;
    out.t_reached = t;
    if (k % per_sample == 0) {
      const double t_sample = p.sample_interval * static_cast<double>(k / per_sample);
      for (int s = 0; s < n; ++s)
        out.outlet[static_cast<std::size_t>(s)].push_back(outlet_of(sys, now, s, t_sample));
      if (opt.on_sample) opt.on_sample(t_sample);
    }
  }
  rep.step_seconds = seconds_since(t0) - factor_seconds;
  rep.factor_seconds = factor_seconds;
  rep.solver = std::string(to_string(opt.solver)) + " + " + to_string(opt.limiter) +
               ", BDF2, chord iteration per step (" + std::to_string(out.factorisations) +
               (out.factorisations == 1 ? " factorisation)" : " factorisations)");

  NetworkSolution& fin = out.final;
  fin.report.solver = rep.solver;
  fin.report.assembly_seconds = rep.assembly_seconds;
  fin.report.solve_seconds = rep.factor_seconds + rep.step_seconds;
  fin.report.corrections = static_cast<int>(std::min<long>(rep.corrections, 1L << 30));
  fin.report.last_change = rep.worst_change;
  fin.report.converged = rep.converged;
  fin.c.resize(static_cast<std::size_t>(n));
  for (int s = 0; s < n; ++s) {
    const Eigen::VectorXd c = sys.species_field(now, s);
    fin.c[static_cast<std::size_t>(s)].assign(c.data(), c.data() + c.size());
  }
  return out;
}

}  // namespace adrsph::reference
