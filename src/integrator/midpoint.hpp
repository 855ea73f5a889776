// Explicit midpoint (second order) for the particle state q = (x, u, rho, C):
//   stage 1   q_h = q0 + dt/2 f(q0)
//   stage 2   q1  = q0 + dt f(q_h)
// without a copy of q0. The store keeps the first-stage rates f0 (ParticleStore::
// keep_first_stage_rates), stage 2 recovers q0 = q_h - dt/2 f0 from them, and a step that
// fails its guards goes back by q0 = q1 - dt f(q_h). The rates are single precision and enter
// the double state only multiplied by dt, so a recovered value differs from the one the step
// started with by the rounding of one addition (1 ulp: ~1e-14 mm in x, far below anything a
// run resolves); keeping the rates costs 4 bytes per value where a copy of q0 costs 8.
//
// A rate that is not finite is taken as zero and counted: the step then fails its guards
// (SphSolver::check_state), and the particle still goes back to a finite start state.
#pragma once

#include <cmath>
#include <cstddef>
#include <limits>

#include "particles/particle_store.hpp"

namespace adrsph::midpoint {

inline bool finite_rate(float r) {
  return std::fabs(r) <= std::numeric_limits<float>::max();  // false for NaN and inf
}
inline double rate_or_zero(float r) {
  return finite_rate(r) ? static_cast<double>(r) : 0.0;
}

// The first stage's velocities of particle i, recovered from its midpoint state (h = dt/2):
// u0 = u_h - h a0, and the transport velocity u0 + du0 its position moved with (eq. (10)).
// Momentum and Shifting: what the scheme's fluid particles carry; `fluid`: whether i is one
// (buffers, and every particle of a prescribed flow, keep u over the step). `rate` reads a
// first-stage rate: rate_or_zero, or one that also counts the non-finite ones.
struct FirstStage {
  double vx, vy;  // u0
  double tx, ty;  // u0 + du0
};
template <bool Momentum, bool Shifting, class Rate>
inline FirstStage first_stage_velocity(const ParticleStore& s, std::size_t i, bool fluid, double h,
                                       Rate&& rate) {
  FirstStage f{s.vx[i], s.vy[i], 0.0, 0.0};
  if constexpr (Momentum)
    if (fluid) {
      f.vx -= h * rate(s.ax_first[i]);
      f.vy -= h * rate(s.ay_first[i]);
    }
  f.tx = f.vx;
  f.ty = f.vy;
  if constexpr (Momentum && Shifting)
    if (fluid) {
      f.tx += rate(s.sx_first[i]);
      f.ty += rate(s.sy_first[i]);
    }
  return f;
}

}  // namespace adrsph::midpoint
