#include "species/reaction_kinetics.hpp"

#include <algorithm>
#include <cmath>

namespace adrsph {

double zone_factor(const Reaction& r, double x, double y) {
  for (const Reaction::Zone& z : r.zones)
    if (x >= z.x0 && x < z.x1 && y >= z.y0 && y < z.y1) return z.factor;
  return 1.0;
}

namespace {

// Michaelis-Menten's implicit solution km ln(C/C0) + C - C0 + k t = 0, for C in (0, C0]:
// Newton in s = ln C (g(s) = km s + e^s - km ln C0 - C0 + k t, convex and increasing, so
// Newton from the right of the root converges monotonically).
double michaelis_menten(double km, double k, double c0, double t) {
  if (km <= 0.0) return std::max(0.0, c0 - k * t);  // zero order
  const double target = km * std::log(c0) + c0 - k * t;
  double s = std::log(c0);  // g(ln C0) = k t >= 0: the right of the root
  for (int it = 0; it < 60; ++it) {
    const double e = std::exp(s);
    const double g = km * s + e - target;
    const double step = g / (km + e);
    s -= step;
    if (std::fabs(step) < 1e-15 * std::max(1.0, std::fabs(s))) break;
  }
  return std::min(c0, std::exp(s));
}

}  // namespace

double react_exact(const Reaction& r, double k_eff, double c0, double t) {
  if (c0 <= 0.0 || k_eff <= 0.0 || t <= 0.0) return c0;
  switch (r.law) {
    case RateLaw::first_order:
      return c0 * std::exp(-k_eff * t);
    case RateLaw::nth_order: {
      const double n = r.order;
      if (n == 1.0) return c0 * std::exp(-k_eff * t);
      const double base = std::pow(c0, 1.0 - n) - (1.0 - n) * k_eff * t;
      if (n < 1.0 && base <= 0.0) return 0.0;  // used up within the step
      return std::pow(base, 1.0 / (1.0 - n));
    }
    case RateLaw::michaelis_menten:
      return michaelis_menten(r.km, k_eff, c0, t);
    case RateLaw::bimolecular:
      break;  // two reactants: bimolecular_extent
  }
  return c0;
}

double bimolecular_extent(double k_eff, double a0, double b0, double t) {
  if (a0 <= 0.0 || b0 <= 0.0 || k_eff <= 0.0 || t <= 0.0) return 0.0;
  // dA/dt = dB/dt = -k A B with A - B = Delta fixed: A(t) = A0 / (1 + B0 phi),
  // phi = -expm1(-k Delta t) / Delta -> k t as Delta -> 0 (no cancellation either way).
  const double delta = a0 - b0;
  const double phi = delta == 0.0 ? k_eff * t : -std::expm1(-k_eff * delta * t) / delta;
  const double a = a0 / (1.0 + b0 * phi);
  return std::min({a0 - a, a0, b0});
}

void react_network(const Case& c, double x, double y, std::span<double> conc, double dt) {
  if (c.species.k > 0.0) conc[0] *= std::exp(-c.species.k * dt);
  for (const Reaction& r : c.reactions) {
    const double k_eff = r.zones.empty() ? r.k : r.k * zone_factor(r, x, y);
    double taken = 0.0;
    if (r.law == RateLaw::bimolecular) {
      double& a = conc[static_cast<std::size_t>(r.reactants[0])];
      double& b = conc[static_cast<std::size_t>(r.reactants[1])];
      taken = bimolecular_extent(k_eff, a, b, dt);
      a = std::max(a - taken, 0.0);
      b = std::max(b - taken, 0.0);
    } else {
      double& a = conc[static_cast<std::size_t>(r.reactants[0])];
      const double after = react_exact(r, k_eff, a, dt);
      taken = a - after;
      a = after;
    }
    for (const int p : r.products) conc[static_cast<std::size_t>(p)] += taken;
  }
}

std::vector<double> batch_state(const Case& c, std::vector<double> c0, double t) {
  constexpr int kSub = 1000;
  for (int i = 0; i < kSub; ++i) react_network(c, 0.0, 0.0, c0, t / kSub);
  return c0;
}

double batch_concentration(const Case& c, double c0, double t, double factor) {
  constexpr int kSub = 1000;
  const double dt = t / kSub;
  Reaction first_order;
  first_order.k = c.species.k;
  double conc = c0;
  for (int i = 0; i < kSub; ++i) {
    conc = react_exact(first_order, c.species.k * factor, conc, dt);
    for (const Reaction& r : c.reactions) conc = react_exact(r, r.k * factor, conc, dt);
  }
  return conc;
}

}  // namespace adrsph
