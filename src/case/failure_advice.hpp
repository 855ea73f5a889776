// What to change in the case when a run fails: advice that names case keys, kept out of the
// solver (which only says what happened: SphSolver::failure()).
#pragma once

#include <string>

#include "adrsph/case.hpp"

namespace adrsph {

// Which guard of SphSolver::step tripped.
enum class FailureKind {
  none,
  non_finite,      // NaN or inf in a position, velocity, density or concentration
  speed,           // a particle faster than 0.5 c0: the flow blew up (acoustic CFL exceeded)
  density,         // density more than 20% from rho0: weak compressibility lost
  concentration,   // C more than c_max / 2 outside [0, c_max]: the species step is unstable
  lost_particles,  // fluid particles found outside the channel at a re-sort
};

// The name run.json gives a kind: "non_finite", "speed", ... ("" for none).
const char* failure_name(FailureKind kind);

// The advice for a failure of `kind` in case `c`; `acoustic_limit` is the stable acoustic
// step of the case [s] (0 without one); `first_step`: it failed at the first step, so the
// start itself is the cause, not the step size.
std::string failure_advice(FailureKind kind, const Case& c, double acoustic_limit,
                           bool first_step = false);

}  // namespace adrsph
