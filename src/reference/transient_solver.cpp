// Transient solve (docs/reference.md, "Transient mode"). Per unit depth every cell balance of
// the steady scheme (finite_volume.hpp) gains the storage term V dC/dt, V = dx dy:
//   V dC/dt + A C + corr(C) = C_in(t) b_in                                          (T1)
// with A the first-order upwind matrix (advection, diffusion, reaction with the [[reaction]]
// tables' slope bound), corr the limited high-order advective flux plus the tables' remainder
// vol (R(C) - a C) (reaction_terms.cpp) and b_in the inlet face's terms per unit inlet value (the
// steady assembly with C_in = 1). In time BDF2 at a constant step dt,
//   V (3 C^{n+1} - 4 C^n + C^{n-1}) / (2 dt) + A C^{n+1} + corr(C^{n+1}) = f_{n+1} b_in,  (T2)
// the limiter iterated within each step by deferred correction as in the steady solve, with
// the step matrix factorised once:
//   (A + 3V/(2dt)) C^{m+1} = V (4 C^n - C^{n-1}) / (2 dt) + f_{n+1} b_in - corr(C^m)     (T3)
// from C^0 = 2 C^n - C^{n-1} until C^m stops changing; then C^{n+1} solves (T2).
//
// The inlet value f_n of step n is the feed's mean over the window [t_n - dt/2, t_n + dt/2].
// Summing (T2) over the steps telescopes the storage term: the amount that enters is
// dt sum_n f_n = int C_in dt exactly (the windows tile the time axis), and, BDF2's symbol
// being s dt = x - x^3/3 + O(x^4) (x = i omega dt), the discrete response has the continuous
// one's mean and variance up to the window sequence's O(dt^2): second order, even for a
// pulse's discontinuous edges.
//
// Start. A channel at rest before t = 0 (c_init steady under C_in(0-): c_init = C_in(0-) and
// k c_init = 0, as in a tracer experiment) has C^{-1} = C^0 as its true history, so BDF2 runs
// from the first step, and the first window, [0, 3dt/2], also carries the feed of [0, dt/2]:
// f_1 = C_in(0-) + int_0^{3dt/2} (C_in - C_in(0-)) dt / dt. Otherwise one implicit-Euler step
// (V (C^1 - C^0) / dt + ... , window [dt/2, 3dt/2]) starts it: second order for a smooth
// start, while BDF2 on a false history would be first order.
#include <Eigen/Sparse>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "adrsph/reference_transient.hpp"
#include "reference/finite_volume.hpp"

namespace adrsph::reference {
namespace {

using detail::SparseMatrix;
using Clock = std::chrono::steady_clock;
using detail::seconds_since;

void check(const TransientProblem& p, int nx, int ny, const TransientOptions& opt) {
  if (nx < 2 || ny < 1) throw std::invalid_argument("reference: need nx >= 2 and ny >= 1");
  if (!p.space.velocity) throw std::invalid_argument("reference: no velocity profile");
  if (!p.inlet_integral) throw std::invalid_argument("reference: no inlet feed");
  if (p.space.source) throw std::invalid_argument("reference: no source in transient mode");
  const Problem& s = p.space;
  if (!(s.D >= 0.0) || !(s.k >= 0.0) || !(s.length > 0.0) || !(s.half_width > 0.0))
    throw std::invalid_argument("reference: need D >= 0, k >= 0, L > 0, R > 0");
  detail::check_time_stepping(opt.dt, p.sample_interval, p.t_end);
}

// A + (alpha V / dt) I: the matrix of an implicit step whose storage term is
// alpha V C^{n+1} / dt (alpha = 3/2 for BDF2, 1 for implicit Euler).
SparseMatrix step_matrix(const SparseMatrix& a, double storage) {
  SparseMatrix m = a;
  for (Eigen::Index k = 0; k < m.outerSize(); ++k)
    for (SparseMatrix::InnerIterator it(m, k); it; ++it)
      if (it.row() == it.col()) it.valueRef() += storage;
  return m;
}

// Rates through the boundaries of field c with inlet value f (docs/reference.md: the steady
// fluxes of finite_volume.hpp), per unit depth.
struct BoundaryRates {
  double inflow = 0.0, outflow = 0.0, reacted = 0.0, held = 0.0;
};

BoundaryRates boundary_rates(const Problem& p, const Grid& g, const std::vector<double>& u_cell,
                             const Eigen::VectorXd& c, double f) {
  const double dy = g.dy(), gx = p.D * dy / g.dx(), vol = g.dx() * dy;
  BoundaryRates r;
  for (int j = 0; j < g.ny; ++j) {
    // Inlet face: advection u_j dy f, diffusion over the half cell 2 gx (f - C_0j).
    r.inflow += u_cell[j] * dy * f + 2.0 * gx * (f - c[g.index(0, j)]);
    r.outflow += u_cell[j] * dy * c[g.index(g.nx - 1, j)];
  }
  r.held = c.sum() * vol;
  r.reacted = p.k * r.held + detail::reaction_total(p, g, c);
  return r;
}

// The outlet face values are the last cells' (zero gradient at x = L): the flux-weighted mean
// sum_j u_j C_j dy / sum_j u_j dy and the plain mean over the section.
OutletRow outlet_of(const Solution& s, const std::vector<double>& u_cell, double t) {
  const Grid& g = s.grid;
  double flux = 0.0, flow = 0.0, sum = 0.0;
  for (int j = 0; j < g.ny; ++j) {
    const double c = s.at(g.nx - 1, j);
    flux += u_cell[j] * g.dy() * c;
    flow += u_cell[j] * g.dy();
    sum += c;
  }
  return {t, flux / flow, sum / g.ny};
}

}  // namespace

namespace detail {

void check_time_stepping(double dt, double sample_interval, double t_end) {
  if (!(dt > 0.0) || !std::isfinite(dt))
    throw std::invalid_argument("reference: the time step must be > 0");
  if (!(sample_interval > 0.0) || !std::isfinite(sample_interval))
    throw std::invalid_argument("reference: the outlet sample interval must be > 0");
  if (!(t_end > 0.0) || !std::isfinite(t_end))
    throw std::invalid_argument("reference: t_end must be > 0");
}

}  // namespace detail

double step_dividing(double dt, double sample_interval) {
  const double n = std::ceil(sample_interval / dt * (1.0 - 1e-12));
  return sample_interval / std::max(1.0, n);
}

OutletRow outlet_row(const Solution& s, const Problem& p, double t) {
  return outlet_of(s, detail::cell_average_velocity(p, s.grid), t);
}

TransientSolution solve_transient(const TransientProblem& p, int nx, int ny,
                                  const TransientOptions& opt) {
  check(p, nx, ny, opt);
  TransientSolution out;
  TransientReport& rep = out.report;
  Solution& s = out.final;
  s.grid = Grid{nx, ny, p.space.length, p.space.half_width};
  const Grid& g = s.grid;
  const double dt = step_dividing(opt.dt, p.sample_interval);
  const long per_sample = std::lround(p.sample_interval / dt);
  // To the first sample at or after t_end, so that the series covers a run of the same case.
  const long steps =
      per_sample * static_cast<long>(std::ceil(p.t_end / p.sample_interval * (1.0 - 1e-12)));
  rep.dt = dt;
  rep.solver = std::string(to_string(opt.solver)) + " + " + to_string(opt.limiter) +
               ", BDF2, deferred correction per step";
  s.report.solver = rep.solver;

  // The steady assembly per unit inlet value gives A and b_in of (T1); the limiter's inlet
  // ghost takes each step's value through `inlet`.
  auto t0 = Clock::now();
  Problem inlet = p.space;
  inlet.inlet = nullptr;
  inlet.c_in = 1.0;
  // The reaction terms' slope bound must be the same in the matrix and in every step's
  // correction, whatever the inlet value: c_max, never the varying c_in (any bound will do
  // for a field that stays at 0).
  if (!(inlet.c_max > 0.0)) inlet.c_max = 1.0;
  const std::vector<double> u_cell = detail::cell_average_velocity(inlet, g);
  const detail::UpwindSystem sys = detail::assemble_upwind_system(inlet, g, u_cell);
  rep.assembly_seconds = seconds_since(t0);

  const double vol = g.dx() * g.dy();
  const double rest = p.inlet_before_start;
  // At rest: c_init is the inlet's value and nothing reacts (every rate law is 0 at C = 0).
  const bool reacts = p.c_init != 0.0 && (p.space.k != 0.0 || !p.space.reactions.empty());
  rep.started_at_rest = p.c_init == rest && !reacts;
  t0 = Clock::now();
  // The matrices outlive their solvers (BiCGSTAB keeps a reference to its matrix).
  const SparseMatrix bdf2_matrix = step_matrix(sys.A, 1.5 * vol / dt);
  const SparseMatrix euler_matrix =
      rep.started_at_rest ? SparseMatrix() : step_matrix(sys.A, vol / dt);
  const auto bdf2 = detail::make_upwind_solver(opt.solver, bdf2_matrix);
  const auto euler =
      rep.started_at_rest ? nullptr : detail::make_upwind_solver(opt.solver, euler_matrix);
  rep.factor_seconds = seconds_since(t0);

  t0 = Clock::now();
  Eigen::VectorXd now = Eigen::VectorXd::Constant(g.cells(), p.c_init), before = now;
  Eigen::VectorXd corr(g.cells()), rhs(g.cells()), c(g.cells());
  // The scale of the deferred-correction tolerance: the largest inlet or initial value met.
  double scale = std::max(std::abs(p.c_init), std::abs(rest));
  TransientBalance& bal = out.balance;
  for (double u : u_cell) bal.flow_rate += u * g.dy();
  bal.held_initial = bal.held_final =
      boundary_rates(inlet, g, u_cell, now, rest).held / bal.flow_rate;
  s.c.assign(now.data(), now.data() + now.size());
  out.outlet.push_back(outlet_of(s, u_cell, 0.0));

  for (long n = 1; n <= steps; ++n) {
    const double t = dt * static_cast<double>(n);
    const bool implicit_euler = n == 1 && !rep.started_at_rest;
    // The window of step n (file comment): [t - dt/2, t + dt/2], from 0 for a start at rest.
    const double lo = n == 1 && rep.started_at_rest ? 0.0 : t - 0.5 * dt, hi = t + 0.5 * dt;
    const double f = (p.inlet_integral(lo, hi) - rest * (hi - lo - dt)) / dt;
    scale = std::max(scale, std::abs(f));
    inlet.c_in = f;

    const Eigen::VectorXd history = implicit_euler
                                        ? Eigen::VectorXd(vol / dt * now)
                                        : Eigen::VectorXd(vol / (2.0 * dt) * (4.0 * now - before));
    rhs = history + f * sys.b;
    c = n == 1 ? now : Eigen::VectorXd(2.0 * now - before);
    detail::UpwindSolver& solver = implicit_euler ? *euler : *bdf2;
    // Nothing to iterate for upwind advection and linear kinetics.
    bool done = opt.limiter == Limiter::upwind && p.space.reactions.empty();
    if (done) {
      c = solver.solve(rhs, c);
      ++rep.corrections;
    }
    double change = 0.0;
    int sweeps = 0;
    while (!done && sweeps < opt.max_corrections) {
      detail::advective_correction(inlet, g, u_cell, opt.limiter, c, corr);
      detail::add_reaction_correction(inlet, g, c, corr);
      const Eigen::VectorXd next = solver.solve(rhs - corr, c);
      change = (next - c).cwiseAbs().maxCoeff() / (scale > 0.0 ? scale : 1.0);
      c = next;
      ++sweeps;
      done = change < opt.tolerance;
    }
    rep.corrections += sweeps;
    rep.max_step_corrections = std::max(rep.max_step_corrections, sweeps);
    rep.worst_change = std::max(rep.worst_change, change);
    rep.converged = rep.converged && done;
    before = now;
    now = c;

    const BoundaryRates r = boundary_rates(inlet, g, u_cell, now, f);
    bal.inflow += dt * r.inflow / bal.flow_rate;
    bal.outflow += dt * r.outflow / bal.flow_rate;
    bal.reacted += dt * r.reacted / bal.flow_rate;
    bal.held_final = r.held / bal.flow_rate;
    rep.steps = n;
    out.t_reached = t;
    if (n % per_sample == 0) {
      s.c.assign(now.data(), now.data() + now.size());
      const double t_sample = p.sample_interval * static_cast<double>(n / per_sample);
      out.outlet.push_back(outlet_of(s, u_cell, t_sample));
      if (opt.on_sample) opt.on_sample(t_sample);
    }
  }
  s.c.assign(now.data(), now.data() + now.size());
  rep.step_seconds = seconds_since(t0);
  s.report.assembly_seconds = rep.assembly_seconds;
  s.report.solve_seconds = rep.factor_seconds + rep.step_seconds;
  s.report.corrections = static_cast<int>(std::min<long>(rep.corrections, 1L << 30));
  s.report.last_change = rep.worst_change;
  s.report.converged = rep.converged;
  return out;
}

}  // namespace adrsph::reference
