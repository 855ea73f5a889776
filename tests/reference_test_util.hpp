// Shared by the reference-solver tests: the reactor problem built in code (docs/benchmark.md,
// section 1) and the closed-form solution of the 1D advection-dispersion-reaction problem.
#pragma once

#include <cmath>

#include "adrsph/reference.hpp"

namespace adrsph::reference::testing {

// The paper's reactor (docs/benchmark.md, section 1) at diffusivity D.
inline Problem reactor(double D) {
  Case c;
  c.species.D = D;
  return problem_from_case(c);
}

// U C' = K C'' - k C on [0, L], C(0) = c0, C'(L) = 0. With m1,2 = (U +- sqrt(U^2 + 4 K k)) / 2K
// (m1 > 0 > m2), C = A e^{m1 (x - L)} + B e^{m2 x}; the inlet gives A e^{-m1 L} + B = c0 and
// the outlet A m1 + B m2 e^{m2 L} = 0, so A = -B (m2 / m1) e^{m2 L} and
// B = c0 / (1 - (m2 / m1) e^{(m2 - m1) L}). (Scaled to keep e^{m1 L} from overflowing.)
struct AxialDispersion1D {
  double U, K, k, L, c0;
  double operator()(double x) const {
    const double s = std::sqrt(U * U + 4.0 * K * k);
    const double m1 = (U + s) / (2.0 * K), m2 = (U - s) / (2.0 * K);
    const double B = c0 / (1.0 - (m2 / m1) * std::exp((m2 - m1) * L));
    const double A = -B * (m2 / m1) * std::exp(m2 * L);
    return A * std::exp(m1 * (x - L)) + B * std::exp(m2 * x);
  }
};

}  // namespace adrsph::reference::testing
