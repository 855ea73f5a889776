// The inlet concentration integrated over a time window, int_a^b C_in(t) dt, exactly for every
// feed shape of species/inlet_feed.hpp (piecewise constant or piecewise linear in t). The
// transient reference (reference/transient_solver.cpp) feeds each time step with the feed's
// mean over the step, so that the amount it injects is the feed's, whatever the step.
#pragma once

#include "adrsph/case.hpp"

namespace adrsph {

// int_a^b C_in(t) dt [mol/m^3 s] for a <= b (0 when a == b); a and b may lie outside the
// feed's features (before t0, beyond a table's ends: the held values).
double feed_integral(const Case::Species& s, double a, double b);

}  // namespace adrsph
