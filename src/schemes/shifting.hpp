// Particle shifting (Lind et al.), eq. (10): du_i = -eps h^2 / dt sum_j V_j grad_i W_ij.
// The pass accumulates g_i = sum_j V_j grad_i W_ij; shifting_velocity() turns it into du and
// caps the displacement per step at shift_max dx (Lind's limiter) so a badly disordered
// start cannot fling particles.
#pragma once

#include <cmath>

namespace adrsph {

struct ShiftingVelocity {
  double coefficient = 0.0;  // eps h^2 / dt
  double max_speed = 0.0;    // shift_max dx / dt

  void operator()(double gx, double gy, double& sx, double& sy) const {
    sx = -coefficient * gx;
    sy = -coefficient * gy;
    const double s = std::sqrt(sx * sx + sy * sy);
    const double scale = s > max_speed ? max_speed / s : 1.0;
    sx *= scale;
    sy *= scale;
  }
};

}  // namespace adrsph
