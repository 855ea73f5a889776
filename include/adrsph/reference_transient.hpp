// The transient mode of the reference (docs/reference.md, "Transient mode"):
//   dC/dt + u(y) dC/dx = D (C_xx + C_yy) - k C - R(C),   C(x, y, 0) = c_init,
//   (R: the case's [[reaction]] tables, iterated inside each step as the steady solve does;
//   one species: a network's is reference_network_transient.hpp),
//   C(0, y, t) = C_in(t) (the same for every y), dC/dn = 0 at the walls, and at x = L the
//   steady solver's outlet: no diffusive flux, advective face value = the last cell's,
// on the steady solver's grid with its spatial discretisation (reference.hpp), BDF2 in time.
// Its outlet series is the SPH run's outlet.csv contract (probes.hpp), so `adrsph rtd` reads
// both alike.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "adrsph/case.hpp"
#include "adrsph/probes.hpp"
#include "adrsph/reference.hpp"

namespace adrsph::reference {

struct TransientProblem {
  Problem space;        // geometry, D, k, u(y); its c_in, inlet and source are not used
  double c_init = 0.0;  // uniform initial C
  // int_a^b C_in(t) dt: each step takes the feed's mean over a window (transient_solver.cpp).
  std::function<double(double a, double b)> inlet_integral;
  double inlet_before_start = 0.0;  // C_in(0-): the inlet value of a channel at rest before t = 0
  double t_end = 1.0;               // [s]; solved to the first sample at or after it
  double sample_interval = 0.01;    // outlet samples at t = 0, interval, 2 interval, ... [s]
};

// The case's reactor (problem_from_case), its species.c_init, its [species.feed] as the inlet,
// time.t_end and output.outlet_interval. Throws std::invalid_argument where problem_from_case
// does (a case the reference cannot solve).
TransientProblem transient_problem_from_case(const Case& c);

struct TransientOptions {
  Limiter limiter = Limiter::van_leer;
  LinearSolver solver = LinearSolver::sparse_lu;
  double dt = 0.01;           // [s]; rounded down to sample_interval / n (n integer)
  double tolerance = 1e-10;   // deferred correction of a step: max |dC| < tolerance * C_scale
  int max_corrections = 100;  // per step
  // Called after every outlet sample with the time reached (progress reports); may be empty.
  std::function<void(double t)> on_sample;
};

// The default step of a case (docs/reference.md, "Transient mode"): a fraction of the
// shortest time scale the outlet response has to carry, the shortest feature of any species'
// feed (a pulse's width, a table's shortest segment) and the sample interval.
inline constexpr double kTransientStepsPerFeature = 10.0;
double default_transient_dt(const Case& c);
// The step actually taken for a requested dt: sample_interval / ceil(sample_interval / dt),
// so that every sample falls on a step.
double step_dividing(double dt, double sample_interval);

struct TransientReport {
  std::string solver;            // e.g. "SparseLU + van_leer, BDF2, deferred correction per step"
  double dt = 0.0;               // the step taken [s]
  long steps = 0;                // up to t_reached
  bool started_at_rest = false;  // BDF2 from the first step; otherwise one implicit-Euler step
  long corrections = 0;          // deferred-correction sweeps (linear solves), all steps
  int max_step_corrections = 0;  // the most any step needed
  double worst_change = 0.0;     // largest final change of a step / C_scale
  bool converged = true;         // every step met the tolerance
  double assembly_seconds = 0.0, factor_seconds = 0.0, step_seconds = 0.0;
};

// What crossed the boundaries over [0, t_reached] (sum over the steps of dt times the step's
// rate) and what the channel holds, per unit depth, divided by the flow rate
// Q = sum_j u_j dy: amounts in mol/m^3 s, comparable with a feed's amount int C_in dt.
struct TransientBalance {
  double inflow = 0.0;   // through x = 0: advection Q C_in plus the Dirichlet face's diffusion
  double outflow = 0.0;  // through x = L: sum_j u_j dy C_j (no diffusive flux)
  double reacted = 0.0;  // k int C dV
  double held_initial = 0.0, held_final = 0.0;  // int C dV
  double flow_rate = 0.0;                       // Q [mm^2/s per unit depth]
};

struct TransientSolution {
  Solution final;  // the field at t_reached (report: solver name, assembly and solve seconds)
  double t_reached = 0.0;
  std::vector<OutletRow> outlet;  // t = 0, sample_interval, ... <= t_reached
  TransientBalance balance;
  TransientReport report;
};

// Throws std::invalid_argument on bad input (grid, coefficients, dt, interval, t_end).
TransientSolution solve_transient(const TransientProblem& p, int nx, int ny,
                                  const TransientOptions& opt = {});

// The outlet of a field as the finite-volume outlet flux sees it: the face value at x = L is
// the last cell's (zero gradient), so C_flow = sum_j u_j C_j dy / sum_j u_j dy over the
// outlet cells, and C_section = sum_j C_j / ny.
OutletRow outlet_row(const Solution& s, const Problem& p, double t);

// DIR/run.json of a transient reference: what `adrsph rtd` reads ("overrides") and what was
// solved ("transient": true, grid, dt, steps, balance, wall_seconds, ...).
void write_transient_run_json(const std::filesystem::path& file, const Case& c,
                              const std::vector<std::string>& overrides, const TransientSolution& s,
                              double wall_seconds);

}  // namespace adrsph::reference
