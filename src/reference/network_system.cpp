// The transport part of the network's equations (network_system.hpp, (N1)): each species'
// first-order upwind system of the single-species assembly (assembly.cpp) with its own D_s,
// k = 0 and no reactions, A_s C_s = b_s, placed on the interleaved numbering
// U[P * N + s]; the limited advective flux of each species (advective_correction); and the
// residual and Jacobian of the whole network.
#include "reference/network_system.hpp"

#include <utility>

namespace adrsph::reference::detail {

NetworkSystem::NetworkSystem(const NetworkProblem& p, const Grid& g)
    : grid_(g),
      n_(static_cast<int>(p.species.size())),
      u_cell_(cell_average_velocity(p.flow, g)),
      kinetics_(p, g) {
  const long cells = g.cells();
  b_unit_ = Eigen::VectorXd::Zero(cells * n_);
  b_ = Eigen::VectorXd::Zero(cells * n_);
  std::vector<Eigen::Triplet<double>> t;
  for (int s = 0; s < n_; ++s) {
    problems_.push_back(p.species_problem(s));
    c_in_.push_back(problems_.back().c_in);
    const UpwindSystem sys = assemble_upwind_system(problems_.back(), g, u_cell_);
    Problem unit = problems_.back();
    unit.c_in = 1.0;
    const Eigen::VectorXd b_unit = assemble_upwind_system(unit, g, u_cell_).b;
    // Entry (P, Q) of A_s becomes (P N + s, Q N + s): blockdiag(A_s) interleaved.
    for (int col = 0; col < sys.A.outerSize(); ++col)
      for (SparseMatrix::InnerIterator it(sys.A, col); it; ++it)
        t.emplace_back(static_cast<int>(it.row()) * n_ + s, col * n_ + s, it.value());
    for (long P = 0; P < cells; ++P) {
      b_unit_[P * n_ + s] = b_unit[P];
      b_[P * n_ + s] = sys.b[P];
    }
  }
  a_.resize(cells * n_, cells * n_);
  a_.setFromTriplets(t.begin(), t.end());
  a_.makeCompressed();
}

Eigen::VectorXd NetworkSystem::species_field(const Eigen::VectorXd& u, int s) const {
  const long cells = grid_.cells();
  Eigen::VectorXd c(cells);
  for (long P = 0; P < cells; ++P) c[P] = u[P * n_ + s];
  return c;
}

Eigen::VectorXd NetworkSystem::residual(const Eigen::VectorXd& u, Limiter limiter) const {
  return residual_from(a_ * u - b_, u, limiter, c_in_);
}

Eigen::VectorXd NetworkSystem::residual(const Eigen::VectorXd& u, Limiter limiter,
                                        const std::vector<double>& c_in) const {
  const long cells = grid_.cells();
  Eigen::VectorXd f = a_ * u;
  for (long P = 0; P < cells; ++P)
    for (int s = 0; s < n_; ++s)
      f[P * n_ + s] -= c_in[static_cast<std::size_t>(s)] * b_unit_[P * n_ + s];
  return residual_from(std::move(f), u, limiter, c_in);
}

// F = (A U - b) + corr(U) + reaction terms, from the transport part A U - b.
Eigen::VectorXd NetworkSystem::residual_from(Eigen::VectorXd f, const Eigen::VectorXd& u,
                                             Limiter limiter,
                                             const std::vector<double>& c_in) const {
  if (limiter != Limiter::upwind) {
    Eigen::VectorXd corr;
    for (int s = 0; s < n_; ++s) {
      Problem ps = problems_[static_cast<std::size_t>(s)];
      ps.c_in = c_in[static_cast<std::size_t>(s)];
      advective_correction(ps, grid_, u_cell_, limiter, species_field(u, s), corr);
      for (long P = 0; P < grid_.cells(); ++P) f[P * n_ + s] += corr[P];
    }
  }
  kinetics_.add_rates(u, f);
  return f;
}

SparseMatrix NetworkSystem::jacobian(const Eigen::VectorXd& u) const {
  std::vector<Eigen::Triplet<double>> t;
  kinetics_.add_jacobian(u, t);
  SparseMatrix dr(a_.rows(), a_.cols());
  dr.setFromTriplets(t.begin(), t.end());  // sums the terms of several reactions
  SparseMatrix J = a_ + dr;
  J.makeCompressed();
  return J;
}

}  // namespace adrsph::reference::detail
