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
  }
  return c0;
}

double batch_concentration(const Case& c, double c0, double t, double factor) {
  constexpr int kSub = 1000;
  const double dt = t / kSub;
  const Reaction first_order{RateLaw::first_order, c.species.k, 1.0, 0.0, {}};
  double conc = c0;
  for (int i = 0; i < kSub; ++i) {
    conc = react_exact(first_order, c.species.k * factor, conc, dt);
    for (const Reaction& r : c.reactions) conc = react_exact(r, r.k * factor, conc, dt);
  }
  return conc;
}

}  // namespace adrsph
