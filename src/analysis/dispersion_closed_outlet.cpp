// The axial-dispersion model with the channel's boundary conditions (dispersion_model.hpp):
//   dC/dt + U dC/dx = K d2C/dx2 on 0 < x < L,  C(0, t) = C_in(t) - base,  K dC/dx(L) = 0,
// C = 0 at t = 0. Finite volumes of width h: the flux through a face is U C_face - K dC/dx,
// with C_face the mean of the two cells (central: second order, monotone while U h / K <= 2),
// at the inlet face U C_in - K (C_0 - C_in) / (h/2), at the outlet face U C_{n-1} alone.
// In time BDF2 (the first step implicit Euler); the inlet value of a step is the feed's mean
// over the step, so a pulse enters with its exact amount whatever the step.
#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "analysis/dispersion_model.hpp"
#include "species/inlet_feed.hpp"

namespace adrsph::analysis {
namespace {

using Matrix = Eigen::SparseMatrix<double>;

// The feed's excess over the base averaged over [t0, t1] (midpoints of 32 sub-intervals;
// a pulse edge inside the step is then placed to 1/32 of the step).
double mean_feed_excess(const Case::Species& s, double t0, double t1) {
  constexpr int kSub = 32;
  double sum = 0.0;
  for (int k = 0; k < kSub; ++k)
    sum += inlet_concentration(s, t0 + (k + 0.5) * (t1 - t0) / kSub) - s.feed.base;
  return sum / kSub;
}

// The shortest feature of the feed in time: a pulse's width, a table's shortest segment.
double feed_feature(const Case::Species& s) {
  if (s.feed.shape == FeedShape::pulse) return s.feed.width;
  double shortest = 1e300;
  for (std::size_t i = 1; i < s.feed.table.size(); ++i)
    shortest = std::min(shortest, s.feed.table[i][0] - s.feed.table[i - 1][0]);
  return shortest;
}

}  // namespace

std::vector<double> closed_outlet_excess(const Case& c, const TaylorAris& m,
                                         const std::vector<double>& times) {
  std::vector<double> out(times.size(), 0.0);
  if (times.empty()) return out;
  const double length = c.geometry.length, u = mean_velocity(c), k = m.dispersion;
  if (!(k > 0.0)) throw std::invalid_argument("the dispersion model needs K > 0");
  // Cell Peclet number U h / K <= 1/2 (at least 200 cells, at most 20000: Pe_L <= 1e4).
  const int n = static_cast<int>(std::clamp(std::ceil(2.0 * m.peclet_length), 200.0, 20000.0));
  const double h = length / n;
  // Steps: 4000 per space time, and 40 per feed feature.
  const double dt = std::min(m.space_time / 4000.0, feed_feature(c.species) / 40.0);

  // dC/dt = -A C + b c_in, A from the face fluxes above.
  std::vector<Eigen::Triplet<double>> a;
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n);
  const double adv = u / (2.0 * h), dif = k / (h * h);
  for (int i = 0; i < n; ++i) {
    // Face i+1/2 (outflow of cell i).
    if (i + 1 < n) {
      a.emplace_back(i, i, adv + dif);
      a.emplace_back(i, i + 1, adv - dif);
      a.emplace_back(i + 1, i, -adv - dif);
      a.emplace_back(i + 1, i + 1, -adv + dif);
    } else {
      a.emplace_back(i, i, u / h);  // outlet face: U C_{n-1}, no dispersive flux
    }
  }
  // Inlet face: U c_in + 2 K (c_in - C_0) / h flows into cell 0.
  a.emplace_back(0, 0, 2.0 * dif);
  b[0] = u / h + 2.0 * dif;
  Matrix A(n, n);
  A.setFromTriplets(a.begin(), a.end());
  Matrix id(n, n);
  id.setIdentity();
  Eigen::SparseLU<Matrix> euler, bdf2;
  euler.compute(Matrix(id / dt + A));
  bdf2.compute(Matrix(1.5 / dt * id + A));
  if (euler.info() != Eigen::Success || bdf2.info() != Eigen::Success)
    throw std::runtime_error("dispersion model: factorisation failed");

  Eigen::VectorXd now = Eigen::VectorXd::Zero(n), before = now;
  double t = 0.0, outlet_before = 0.0;
  std::size_t next = 0;
  while (next < times.size() && times[next] <= 0.0) out[next++] = 0.0;
  for (long step = 0; next < times.size(); ++step) {
    const double c_in = mean_feed_excess(c.species, t, t + dt);
    Eigen::VectorXd rhs;
    if (step == 0) {
      rhs = now / dt + b * c_in;
      before = now;
      now = euler.solve(rhs);
    } else {
      rhs = (2.0 * now - 0.5 * before) / dt + b * c_in;
      before = now;
      now = bdf2.solve(rhs);
    }
    t += dt;
    const double outlet = now[n - 1];  // zero gradient at x = L: the last cell's value
    // Linear in time between the steps around each requested instant.
    while (next < times.size() && times[next] <= t) {
      const double w = (times[next] - (t - dt)) / dt;
      out[next++] = outlet_before + w * (outlet - outlet_before);
    }
    outlet_before = outlet;
  }
  return out;
}

}  // namespace adrsph::analysis
