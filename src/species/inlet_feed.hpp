// The inlet concentration as a function of time, `[species.feed]` of a case
// (cases/README.md): the value the inflow buffer carries, a Dirichlet condition at x = 0.
//   constant  C_in(t) = c_in
//   step      C_in(t) = base for t < t0, c_in from t0 on
//   pulse     C_in(t) = c_in for t0 <= t < t0 + width, base otherwise
//   table     C_in(t) linear between the (t, C) points, held at the end values beyond them
// The moments are those of the feed's excess over `base`, the input signal of a
// residence-time measurement (analysis/rtd.hpp): its amount, mean time and variance.
#pragma once

#include "adrsph/case.hpp"

namespace adrsph {

double inlet_concentration(const Case::Species& s, double t);

// Whether the inlet value changes in time (a constant feed costs nothing per step).
inline bool feed_varies(const Case::Species& s) {
  return s.feed.shape != FeedShape::constant;
}

// Largest inlet value the feed reaches (a bound of the concentration guard).
double feed_max(const Case::Species& s);

struct FeedMoments {
  double amount = 0.0;    // integral of (C_in - base) dt [mol/m^3 s]; infinite for a step
  double mean = 0.0;      // its mean time [s]
  double variance = 0.0;  // its variance [s^2]
};
// Of a pulse or a table (exact for the piecewise-linear table); a step and a constant feed
// have no finite amount: amount = infinity, mean and variance NaN.
FeedMoments feed_moments(const Case::Species& s);

}  // namespace adrsph
