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

// Transport velocity of the first stage of particle i (u0 + du0 for a moving fluid particle,
// u otherwise) from its midpoint state, u0 = u_h - dt/2 a0 (h = dt/2). Momentum and Shifting:
// what the scheme's fluid particles carry; `fluid`: whether i is one.
template <bool Momentum, bool Shifting>
inline void first_stage_transport(const ParticleStore& s, std::size_t i, bool fluid, double h,
                                  double& tx, double& ty) {
  tx = s.vx[i];
  ty = s.vy[i];
  if constexpr (Momentum) {
    if (!fluid) return;  // buffers (and a prescribed flow) keep u over the step
    tx -= h * rate_or_zero(s.ax_first[i]);
    ty -= h * rate_or_zero(s.ay_first[i]);
    if constexpr (Shifting) {
      tx += rate_or_zero(s.sx_first[i]);
      ty += rate_or_zero(s.sy_first[i]);
    }
  }
}

}  // namespace adrsph::midpoint
