// The reaction terms of the network (network_system.hpp, (N1) and (N2)): the rate laws of
// case.hpp (docs/kinetics.md) at the cell centres, and their exact derivatives with respect to
// every reactant concentration:
//   first_order   R = k a            dR/da = k
//   nth_order     R = k a^n          dR/da = n k a^(n-1)           (n >= 1)
//   michaelis_m.  R = k a / (km + a) dR/da = k km / (km + a)^2     (km > 0)
//   bimolecular   R = k a b          dR/da = k b,  dR/db = k a
// Reaction r consumes R_r of each reactant and makes R_r of each product: species s gets
// V nu_rs R_r in (N1) (nu = +1 reactant, -1 product) and V nu_rs dR_r/dC_t in row s, column t
// of the cell's block of J. As in reaction_terms.cpp a negative concentration (an iterate can
// overshoot) enters the laws as 0, a = max(C_a, 0); the derivative is taken at that clipped
// value, i.e. for C < 0 the slope of the law at 0+ (exact wherever C >= 0, where the solution
// lies; it keeps a first-order term's slope k, so the linear part of J never drops out).
// Zones as in reaction_terms.cpp: k times the factor of the first zone holding the cell
// centre (x0 <= x < x1, y0 <= y < y1), k outside every zone.
#include <algorithm>
#include <cmath>

#include "reference/network_system.hpp"

namespace adrsph::reference::detail {
namespace {

// R and dR/dC of its reactants (slope[q] for reactants[q]) at the concentrations c of a cell.
struct RateSlope {
  double rate = 0.0;
  double slope[2] = {0.0, 0.0};
};

RateSlope rate_and_slope(const Reaction& r, double k, const double* c) {
  RateSlope out;
  const double a = std::max(c[r.reactants[0]], 0.0);
  switch (r.law) {
    case RateLaw::first_order:
      out.rate = k * a;
      out.slope[0] = k;
      break;
    case RateLaw::nth_order: {
      out.rate = k * std::pow(a, r.order);
      out.slope[0] = r.order * k * std::pow(a, r.order - 1.0);  // k at a = 0 for n = 1
      break;
    }
    case RateLaw::michaelis_menten: {
      const double den = r.km + a;
      out.rate = k * a / den;
      out.slope[0] = k * r.km / (den * den);
      break;
    }
    case RateLaw::bimolecular: {
      const double b = std::max(c[r.reactants[1]], 0.0);
      out.rate = k * a * b;
      out.slope[0] = k * b;
      out.slope[1] = k * a;
      break;
    }
  }
  return out;
}

}  // namespace

NetworkKinetics::NetworkKinetics(const NetworkProblem& p, const Grid& g)
    : reactions_(p.reactions),
      n_(static_cast<int>(p.species.size())),
      cells_(g.cells()),
      vol_(g.dx() * g.dy()) {
  k_.resize(reactions_.size());
  for (std::size_t r = 0; r < reactions_.size(); ++r) {
    const Reaction& re = reactions_[r];
    linear_ = linear_ &&
              (re.law == RateLaw::first_order || (re.law == RateLaw::nth_order && re.order == 1.0));
    k_[r].resize(static_cast<std::size_t>(cells_));
    for (int i = 0; i < g.nx; ++i)
      for (int j = 0; j < g.ny; ++j)
        k_[r][static_cast<std::size_t>(g.index(i, j))] =
            re.k * zone_factor_at(re, g.xc(i), g.yc(j));
  }
}

void NetworkKinetics::add_rates(const Eigen::VectorXd& u, Eigen::VectorXd& f) const {
  for (std::size_t r = 0; r < reactions_.size(); ++r) {
    const Reaction& re = reactions_[r];
    for (long P = 0; P < cells_; ++P) {
      const long row = P * n_;
      const double vr = vol_ * rate_and_slope(re, k_[r][static_cast<std::size_t>(P)], &u[row]).rate;
      for (int s : re.reactants) f[row + s] += vr;
      for (int s : re.products) f[row + s] -= vr;
    }
  }
}

void NetworkKinetics::add_jacobian(const Eigen::VectorXd& u,
                                   std::vector<Eigen::Triplet<double>>& t) const {
  for (std::size_t r = 0; r < reactions_.size(); ++r) {
    const Reaction& re = reactions_[r];
    for (long P = 0; P < cells_; ++P) {
      const long row = P * n_;
      const RateSlope rs = rate_and_slope(re, k_[r][static_cast<std::size_t>(P)], &u[row]);
      for (std::size_t q = 0; q < re.reactants.size(); ++q) {
        const int col = static_cast<int>(row + re.reactants[q]);
        const double d = vol_ * rs.slope[q];
        for (int s : re.reactants) t.emplace_back(static_cast<int>(row + s), col, d);
        for (int s : re.products) t.emplace_back(static_cast<int>(row + s), col, -d);
      }
    }
  }
}

double NetworkKinetics::turnover(const Eigen::VectorXd& u, std::size_t r) const {
  double total = 0.0;
  for (long P = 0; P < cells_; ++P)
    total += rate_and_slope(reactions_[r], k_[r][static_cast<std::size_t>(P)], &u[P * n_]).rate;
  return vol_ * total;
}

}  // namespace adrsph::reference::detail
