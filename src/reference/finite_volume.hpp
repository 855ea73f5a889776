// Internal: the cell-centred finite-volume discretisation of the reference problem
// (docs/benchmark.md, section 5). Each cell balance, per unit depth:
//   [F_e - F_w]_advection - [G_e - G_w]_diffusion + k C_P dx dy = S_P dx dy
// advective flux F = u_j dy C_face (u > 0: upwind side), diffusive flux G = D dA dC/dn
// (second-order central), inlet face: Dirichlet, walls and outlet: zero diffusive flux,
// outlet advective face value = C_P (zero gradient).
#pragma once

#include <Eigen/Sparse>
#include <chrono>
#include <limits>
#include <memory>
#include <vector>

#include "adrsph/reference.hpp"

namespace adrsph::reference::detail {

using SparseMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

// Cell-averaged velocity of row j, (1/dy) * integral of u over the cell (Simpson's rule:
// exact for the parabola), so that sum_j u_j dy is the exact flow rate.
std::vector<double> cell_average_velocity(const Problem& p, const Grid& g);

struct UpwindSystem {
  SparseMatrix A;     // first-order upwind advection + central diffusion + reaction
  Eigen::VectorXd b;  // inlet Dirichlet terms + source
};
UpwindSystem assemble_upwind_system(const Problem& p, const Grid& g,
                                    const std::vector<double>& u_cell);

// Net high-order correction of the advective flux per cell, (Fc_e - Fc_w), with
// Fc_{i+1/2} = u_j dy * slope_i / 2 (limited slope of cell i; ghost C_{-1} = 2 C_in - C_0).
// Moving it to the right-hand side is the deferred correction.
void advective_correction(const Problem& p, const Grid& g, const std::vector<double>& u_cell,
                          Limiter limiter, const Eigen::VectorXd& c, Eigen::VectorXd& corr);

// The [[reaction]] terms (reaction_terms.cpp), linearised about a bound of their slope:
// R(C) = a C + (R(C) - a C), a >= dR/dC over [0, c_max] in each cell, the first part on the
// matrix diagonal (reaction_slope, per unit volume), the second moved to the right-hand side
// and iterated with the advective correction (reaction_correction adds vol (R - a C)).
// A first-order reaction is exactly linear: its correction is zero.
double reaction_slope(const Problem& p, double x, double y);
void add_reaction_correction(const Problem& p, const Grid& g, const Eigen::VectorXd& c,
                             Eigen::VectorXd& corr);
// sum over the cells of vol R(C): what the [[reaction]] tables consume per unit time and depth.
double reaction_total(const Problem& p, const Grid& g, const Eigen::VectorXd& c);

// One interface over the two Eigen solvers (linear_solver.cpp): factorise or precondition
// once, solve many times. The matrix must outlive the solver (BiCGSTAB keeps a reference).
class UpwindSolver {
 public:
  virtual ~UpwindSolver() = default;
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& rhs, const Eigen::VectorXd& guess) = 0;
};
std::unique_ptr<UpwindSolver> make_upwind_solver(LinearSolver kind, const SparseMatrix& A);

// k(x, y) / k of a reaction: the first zone holding the point (x0 <= x < x1, y0 <= y < y1),
// else 1 (reaction_terms.cpp).
double zone_factor_at(const Reaction& r, double x, double y);

// Under-relaxation of an iteration x += relax * dx: halved whenever the change has not
// improved for 10 iterations (down to 1/16), which breaks the limit cycles a limiter's
// switches (minmod's kinks) can leave near 1e-10.
struct StallRelaxation {
  double relax = 1.0;
  double best = std::numeric_limits<double>::infinity();
  int since_best = 0;
  void update(double change) {
    if (change < best) {
      best = change;
      since_best = 0;
    } else if (++since_best >= 10 && relax > 0.1) {
      relax *= 0.5;
      since_best = 0;
    }
  }
};

// Seconds of wall time since t0 (the solvers' reports).
inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The time stepping of a transient solve: throws std::invalid_argument unless dt, the
// outlet sample interval and t_end are > 0 and finite (transient_solver.cpp).
void check_time_stepping(double dt, double sample_interval, double t_end);

// Limited slope from the upwind and downwind differences (TVD region, second order
// where smooth: both return the true difference for dl == dr).
double limited_slope(Limiter limiter, double dl, double dr);

}  // namespace adrsph::reference::detail
