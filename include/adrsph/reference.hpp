// The reference solution (docs/benchmark.md, section 5; the paper's COMSOL role): the steady
// problem
//   u(y) dC/dx = D (C_xx + C_yy) - k C + S(x, y)
// on x in [0, L], y in [-R, R], C = C_in(y) at x = 0, dC/dn = 0 at the walls and the outlet,
// on a structured cell-centred finite-volume grid, solved with Eigen's sparse solvers.
// S is zero for the reactor; tests use it for manufactured solutions. Shares no code with
// the SPH path (docs/benchmark.md, section 5).
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "adrsph/case.hpp"
#include "adrsph/probes.hpp"

namespace adrsph::reference {

// The continuous problem. `velocity` must be > 0 on (-R, R) (advection along +x only).
struct Problem {
  double length = 100.0;    // L [mm]
  double half_width = 5.0;  // R [mm]
  double D = 10.0;          // diffusivity [mm^2/s]
  double k = 1.462;         // first-order rate [1/s]
  double c_in = 2.0;        // inlet concentration (used when `inlet` is empty)
  double u_bulk = 100.0;    // recorded in the output; u_max = 2 u_bulk (docs/benchmark.md, 1)
  std::function<double(double y)> velocity;          // u(y) [mm/s]
  std::function<double(double y)> inlet;             // C(0, y); empty: c_in
  std::function<double(double x, double y)> source;  // S(x, y); empty: 0
  // The [[reaction]] tables of the case, consuming R(C; x, y) besides k C (reaction_terms.cpp):
  // first order, n-th order with n >= 1, Michaelis-Menten with km > 0, zones at cell centres.
  std::vector<Reaction> reactions;
  // The largest C the field can take, over which the reaction terms' slope is bounded
  // (reaction_terms.cpp); 0: c_in, the steady maximum (the inlet, as reactions only consume).
  // The transient mode sets it to the larger of the initial value and the feed's maximum.
  double c_max = 0.0;

  double inlet_value(double y) const { return inlet ? inlet(y) : c_in; }
  double peclet() const { return u_bulk * length / D; }
};

// The reactor of a case: parabolic u(y) = u_max (1 - (y/R)^2), u_max = 2 u_bulk
// (docs/benchmark.md, section 1). Throws std::invalid_argument for a [[reaction]] whose rate
// has an unbounded slope at C = 0 (n-th order with n < 1, Michaelis-Menten with km = 0).
Problem problem_from_case(const Case& c);
std::function<double(double)> parabolic_profile(double u_max, double half_width);

// Cell-centred grid: nx x ny cells, centres x_i = (i + 1/2) dx, y_j = -R + (j + 1/2) dy.
struct Grid {
  int nx = 1600, ny = 160;
  double length = 100.0, half_width = 5.0;
  double dx() const { return length / nx; }
  double dy() const { return 2.0 * half_width / ny; }
  double xc(int i) const { return (i + 0.5) * dx(); }
  double yc(int j) const { return -half_width + (j + 0.5) * dy(); }
  // Unknown index: x-major, so the upwind neighbour (i - 1) precedes (good for ILU).
  long index(int i, int j) const { return static_cast<long>(i) * ny + j; }
  long cells() const { return static_cast<long>(nx) * ny; }
};

// Face value of the advected C: first-order upwind, or upwind plus a limited slope
// (TVD, second order where smooth), applied by deferred correction.
enum class Limiter { upwind, minmod, van_leer };
enum class LinearSolver { sparse_lu, bicgstab_ilut };

struct SolverOptions {
  Limiter limiter = Limiter::van_leer;
  LinearSolver solver = LinearSolver::sparse_lu;
  double tolerance = 1e-11;   // deferred correction stops when max |dC| < tolerance * C_scale
  int max_corrections = 400;  // deferred correction iterations
};

struct SolveReport {
  std::string solver;  // e.g. "SparseLU + van_leer deferred correction"
  double assembly_seconds = 0.0;
  double solve_seconds = 0.0;  // factorisation + all correction sweeps
  int corrections = 0;         // deferred correction iterations done
  double last_change = 0.0;    // max |dC| / C_scale of the last iteration (unrelaxed)
  double relaxation = 1.0;     // final under-relaxation of the correction (halved on stalls)
  double residual = 0.0;       // ||A(C) C - b||_2 / ||b||_2 of the full (limited) scheme
  bool converged = false;
};

struct Solution {
  Grid grid;
  std::vector<double> c;  // cell values, grid.index(i, j)
  SolveReport report;
  double at(int i, int j) const { return c[static_cast<std::size_t>(grid.index(i, j))]; }
};

Solution solve_steady(const Problem& p, int nx, int ny, const SolverOptions& opt = {});

// Sampling (docs/benchmark.md, section 4). C(x, y) bilinear between cell centres; towards x = 0 the
// Dirichlet value, beyond the last centre the zero-gradient face value; likewise in y.
double sample(const Solution& s, const Problem& p, double x, double y);
// Area average over y in [-R, R]: sum_j C_ij dy / 2R per column, linear in x between centres.
double section_average(const Solution& s, const Problem& p, double x);
ProbeTable probe_table(const Solution& s, const Problem& p);
StationTable station_table(const Solution& s, const Problem& p);

// DIR/reference.h5: datasets x (nx), y (ny), C (ny x nx, row j = y_j); attributes
// D, k, u_bulk, nx, ny (plus L, R, c_in).
void write_reference_h5(const std::filesystem::path& file, const Solution& s, const Problem& p);

// reference.h5 read back (tests, post-processing). Throws std::runtime_error naming the file.
struct ReferenceField {
  int nx = 0, ny = 0;
  std::vector<double> x, y, c;  // c[j * nx + i] = C(x_i, y_j)
  double D = 0.0, k = 0.0, u_bulk = 0.0, c_in = 0.0, length = 0.0, half_width = 0.0;
};
ReferenceField read_reference_h5(const std::filesystem::path& file);

// DIR/reference.json: grid, D, k, c_in, u_bulk, Pe, solver, timings, residual, stations.
void write_reference_json(const std::filesystem::path& file, const std::string& case_name,
                          const Solution& s, const Problem& p);

// Grid convergence (docs/benchmark.md, section 5): the same problem on several grids, finest last.
struct ConvergenceLevel {
  int nx = 0, ny = 0;
  StationTable stations;
  SolveReport report;
};
// Relative change of station m between levels l - 1 and l: |f_l - f_{l-1}| / |f_l|.
double relative_change(const std::vector<ConvergenceLevel>& levels, std::size_t l, std::size_t m);
// Observed order from levels l - 2, l - 1, l (each refined by 2): log2(|f1 - f0| / |f2 - f1|);
// NaN when the differences vanish.
double observed_order(const std::vector<ConvergenceLevel>& levels, std::size_t l, std::size_t m);

// The criterion of docs/benchmark.md, section 5: every station of grid `nx` changes by
// < `tolerance` relative on the next finer level. `checked` is false when there is no finer level.
struct ConvergenceVerdict {
  bool checked = false;
  bool pass = false;
  double max_change = 0.0;
};
ConvergenceVerdict convergence_verdict(const std::vector<ConvergenceLevel>& levels, int nx,
                                       double tolerance = 1e-4);
// Markdown table: grid, solve seconds, C_mean per station, relative change and observed
// order per station.
std::string convergence_table(const std::vector<ConvergenceLevel>& levels);

const char* to_string(Limiter l);
const char* to_string(LinearSolver s);

}  // namespace adrsph::reference
