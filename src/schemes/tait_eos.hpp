// Tait equation of state, eq. (2) of the paper, plus the background pressure p_b of the
// conventional scheme (docs/benchmark.md, section 2: p_b = background_pressure * rho0 c0^2).
#pragma once

#include <cmath>

namespace adrsph {

struct TaitEos {
  double rho0 = 1.0, c0 = 1.0, gamma = 7.0, p_background = 0.0;

  double stiffness() const { return rho0 * c0 * c0 / gamma; }
  // p = rho0 c0^2 / gamma ((rho / rho0)^gamma - 1) + p_b          eq. (2)
  double pressure(double rho) const {
    return stiffness() * (power(rho / rho0) - 1.0) + p_background;
  }
  // (rho / rho0)^gamma: the paper's gamma = 7 by multiplications (pow was 5% of a step).
  double power(double r) const {
    if (gamma == 7.0) {
      const double r2 = r * r;
      return r2 * r2 * r2 * r;
    }
    return std::pow(r, gamma);
  }
  // Inverse of pressure(): the density a boundary particle needs to carry pressure p.
  double density(double p) const {
    return rho0 * std::pow((p - p_background) / stiffness() + 1.0, 1.0 / gamma);
  }
};

}  // namespace adrsph
