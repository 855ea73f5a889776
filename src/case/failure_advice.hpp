// What to change in the case when a run fails: advice that names case keys, kept out of the
// solver (which only says what happened: SphSolver::failure()).
#pragma once

#include <string>

#include "adrsph/case.hpp"

namespace adrsph {

enum class FailureKind {
  none,
  unstable_step,   // non-finite state, speed, density or concentration out of bounds
  lost_particles,  // fluid particles found outside the channel at a re-sort
};

// The advice for a failure of `kind` in case `c`; `acoustic_limit` is the stable acoustic
// step of the case [s] (0 without one).
std::string failure_advice(FailureKind kind, const Case& c, double acoustic_limit);

}  // namespace adrsph
