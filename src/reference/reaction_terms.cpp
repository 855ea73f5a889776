// The [[reaction]] terms of the reference (finite_volume.hpp): the rate laws of
// docs/kinetics.md evaluated at cell centres, with a bound of their slope over [0, c_max]
// (Problem::c_max, or c_in: the steady solution stays in [0, c_in], the inlet being the
// largest value and reactions only consuming; a transient one in [0, max(c_init, feed)]).
// The iteration (A + a) C_new = b - vol (R(C) - a C) contracts because 0 <= dR/dC <= a.
#include <algorithm>
#include <cmath>

#include "reference/finite_volume.hpp"

namespace adrsph::reference::detail {
double zone_factor_at(const Reaction& r, double x, double y) {
  for (const Reaction::Zone& z : r.zones)
    if (x >= z.x0 && x < z.x1 && y >= z.y0 && y < z.y1) return z.factor;
  return 1.0;
}

namespace {

double rate(const Reaction& r, double k, double c) {
  c = std::max(c, 0.0);
  switch (r.law) {
    case RateLaw::first_order:
      return k * c;
    case RateLaw::nth_order:
      return k * std::pow(c, r.order);
    case RateLaw::michaelis_menten:
      return k * c / (r.km + c);
    case RateLaw::bimolecular:
      break;  // two species: the network reference (reference_network.hpp)
  }
  return 0.0;
}

// max of dR/dC over [0, c_max]: k; n k c_max^(n-1) (n >= 1); k / km at C = 0.
double slope_bound(const Reaction& r, double k, double c_max) {
  switch (r.law) {
    case RateLaw::first_order:
      return k;
    case RateLaw::nth_order:
      return r.order * k * std::pow(std::max(c_max, 0.0), r.order - 1.0);
    case RateLaw::michaelis_menten:
      return k / r.km;
    case RateLaw::bimolecular:
      break;
  }
  return 0.0;
}

double c_bound(const Problem& p) {
  return p.c_max > 0.0 ? p.c_max : p.c_in;
}

}  // namespace

double reaction_slope(const Problem& p, double x, double y) {
  double a = 0.0;
  for (const Reaction& r : p.reactions)
    a += slope_bound(r, r.k * zone_factor_at(r, x, y), c_bound(p));
  return a;
}

double reaction_total(const Problem& p, const Grid& g, const Eigen::VectorXd& c) {
  if (p.reactions.empty()) return 0.0;
  double total = 0.0;
  for (int i = 0; i < g.nx; ++i)
    for (int j = 0; j < g.ny; ++j)
      for (const Reaction& r : p.reactions)
        total += rate(r, r.k * zone_factor_at(r, g.xc(i), g.yc(j)), c[g.index(i, j)]);
  return total * g.dx() * g.dy();
}

void add_reaction_correction(const Problem& p, const Grid& g, const Eigen::VectorXd& c,
                             Eigen::VectorXd& corr) {
  if (p.reactions.empty()) return;
  const double vol = g.dx() * g.dy(), c_max = c_bound(p);
  for (int i = 0; i < g.nx; ++i)
    for (int j = 0; j < g.ny; ++j) {
      const long P = g.index(i, j);
      const double x = g.xc(i), y = g.yc(j);
      double excess = 0.0;  // R(C) - a C
      for (const Reaction& r : p.reactions) {
        const double k = r.k * zone_factor_at(r, x, y);
        excess += rate(r, k, c[P]) - slope_bound(r, k, c_max) * c[P];
      }
      corr[P] += vol * excess;
    }
}

}  // namespace adrsph::reference::detail
