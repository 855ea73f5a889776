// Internal: the discrete reaction network of the reference (reference_network.hpp). Unknowns
// U = (C_s at cell P) are numbered cell-major, species-minor, U[P * N + s] (P = grid.index(i, j),
// N species), so that the reaction coupling of the species of one cell is an N x N block on
// the diagonal and the whole Jacobian stays a narrow band (species-major numbering puts the
// coupling N x cells apart and SparseLU's fill explodes).
//
// Per unit depth every species obeys the cell balance of the single-species scheme
// (finite_volume.hpp) with its own D_s and without k, plus the network's reaction terms:
//   F_s,P(U) = [A_s C_s + corr_s(C_s) - b_s]_P + V sum_r nu_rs R_r(C_P) = 0            (N1)
// with A_s the first-order upwind advection and central diffusion of species s, corr_s the
// limited high-order part of its advective flux (advective_correction), b_s its inlet terms,
// V = dx dy the cell volume, nu_rs = +1 for a reactant and -1 for a product of reaction r
// (nu summed when a species appears more than once) and R_r evaluated at the cell centre with
// the reaction's zone factor. Newton's method uses
//   J(U) = blockdiag(A_s) + V dR/dC(U)                                                   (N2)
// (the limiter's derivative left out: it is the deferred correction, see network_solver.cpp).
#pragma once

#include <Eigen/Sparse>
#include <vector>

#include "adrsph/reference_network.hpp"
#include "reference/finite_volume.hpp"

namespace adrsph::reference::detail {

// Throws std::invalid_argument unless the network is one the solver takes: >= 1 species with
// D >= 0, reactants and products indices into `species`, one reactant (first_order, nth_order
// with n >= 1, michaelis_menten with km > 0) or two different ones (bimolecular), k >= 0.
void check_network(const NetworkProblem& p);

// The reaction terms V sum_r nu_rs R_r(C_P) of (N1) and their derivative, the second part of
// (N2), with the rate constants k_r(x_P, y_P) (zone factors applied) tabulated once per cell.
class NetworkKinetics {
 public:
  NetworkKinetics(const NetworkProblem& p, const Grid& g);
  // True when every rate is linear in C (first order, or n-th order with n = 1): then the
  // reaction part of J does not depend on U.
  bool linear() const { return linear_; }
  // f[P * N + s] += V sum_r nu_rs R_r(C_P).
  void add_rates(const Eigen::VectorXd& u, Eigen::VectorXd& f) const;
  // Triplets (P * N + s, P * N + t, V sum_r nu_rs dR_r/dC_t) of every cell: the same positions
  // for every U (entries may be zero), so that J keeps one sparsity pattern.
  void add_jacobian(const Eigen::VectorXd& u, std::vector<Eigen::Triplet<double>>& t) const;
  // sum over the cells of V R_r(C_P): what reaction r turns over per unit time and depth.
  double turnover(const Eigen::VectorXd& u, std::size_t r) const;

 private:
  std::vector<Reaction> reactions_;
  int n_;
  long cells_;
  double vol_;
  bool linear_ = true;
  std::vector<std::vector<double>> k_;  // k_[r][P] = k_r * zone factor at the centre of P
};

// The transport of every species on the interleaved numbering, and the residual (N1).
class NetworkSystem {
 public:
  NetworkSystem(const NetworkProblem& p, const Grid& g);
  int species() const { return n_; }
  const Grid& grid() const { return grid_; }
  const Eigen::VectorXd& b() const { return b_; }
  const NetworkKinetics& kinetics() const { return kinetics_; }
  // Species s alone: geometry, velocity, D_s, c_in,s (NetworkProblem::species_problem).
  const Problem& species_problem(int s) const { return problems_[static_cast<std::size_t>(s)]; }
  // The problem's inlet values c_in,s, one per species.
  const std::vector<double>& inlet() const { return c_in_; }
  // F(U) of (N1) with the limiter `limiter` (upwind: corr = 0), at the problem's inlet values.
  Eigen::VectorXd residual(const Eigen::VectorXd& u, Limiter limiter) const;
  // F(U) of (N1) with inlet values c_in[s] in place of the problem's (the transient mode's
  // feeds): b_s is linear in c_in,s (the inlet face's advection and diffusion), and the
  // limiter's inlet ghost takes c_in[s].
  Eigen::VectorXd residual(const Eigen::VectorXd& u, Limiter limiter,
                           const std::vector<double>& c_in) const;
  // J(U) of (N2).
  SparseMatrix jacobian(const Eigen::VectorXd& u) const;
  // The volume of a cell, V = dx dy, and the cell-average velocity of each row.
  double cell_volume() const { return grid_.dx() * grid_.dy(); }
  const std::vector<double>& cell_velocity() const { return u_cell_; }
  // C_s of the interleaved U, as one vector over the cells (grid.index order).
  Eigen::VectorXd species_field(const Eigen::VectorXd& u, int s) const;

 private:
  Eigen::VectorXd residual_from(Eigen::VectorXd f, const Eigen::VectorXd& u, Limiter limiter,
                                const std::vector<double>& c_in) const;

  Grid grid_;
  int n_;
  std::vector<Problem> problems_;  // species_problem(s): D_s, c_in,s, k = 0, no reactions
  std::vector<double> u_cell_;
  SparseMatrix a_;          // blockdiag(A_s) on the interleaved numbering
  Eigen::VectorXd b_unit_;  // b of every species for c_in,s = 1
  std::vector<double> c_in_;
  Eigen::VectorXd b_;  // b at c_in_
  NetworkKinetics kinetics_;
};

}  // namespace adrsph::reference::detail
