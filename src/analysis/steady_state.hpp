// Steady state, two conditions (docs/steady-state.md):
//
// 1. The slow streamlines have been swept. Near the walls the flow is slow: fluid that was in
//    the channel at t = 0 stays there for L / u(y), arbitrarily long as y -> +-R, and a
//    window test sees its slow drift as noise. So no run is steady before t_min, the time at
//    which a bound on the cold-start transient of the outlet section average falls below
//    time.steady_sweep_tol (relative). Pure advection-reaction in the analytic profile:
//    a streamline not yet swept (u(y) t < L) holds the initial fluid, c_init e^{-kt}, instead
//    of its steady value c_in e^{-kL/u(y)}; integrated over y and divided by the steady
//    section average this bounds the outlet's remaining transient (cold_start_transient()).
//    Diffusion only mixes the slow fluid with swept fluid sooner, so the bound is
//    conservative at low Pe; it is the same for warm-started runs, whose WCSPH flow starts
//    from the same state at t = 0 (a warm start changes C, not how long the flow needs).
//    With [[reaction]] tables the same bound takes the batch solution of the case's kinetics
//    (species/reaction_kinetics.hpp) in place of c exp(-kt).
//    A network of several species takes the batch state of all of them (the largest bound
//    over the species counts).
//    A step feed (species.feed.shape = "step") starts the same sweep at its step instant t0,
//    from a field of at most max(c_init, base): t_min is counted from t0.
// 2. The probe profiles stop changing. Single snapshots carry sampling noise (rows of
//    particles slide past the probe points), so the test compares the MEAN probe profiles
//    over two consecutive windows [t - 2w, t - w] and [t - w, t], sampled at jittered
//    instants (simulation.cpp); the largest change of any probe's window mean, relative to
//    the inlet concentration, must be below time.steady_tol.
#pragma once

#include <algorithm>
#include <cmath>
#include <deque>

#include "adrsph/case.hpp"
#include "adrsph/checkpoint.hpp"
#include "adrsph/probes.hpp"

namespace adrsph {

struct SteadyCriterion {
  double tol = 1e-3;    // largest allowed change of a window mean, relative to `scale`
  double window = 0.5;  // [s] averaging window
  double t_min = 0.0;   // [s] no verdict before this time
  double scale = 1.0;   // concentration scale (c_in)
};

// The concentration scale the steady test's change is relative to: the largest inlet value
// of the species.
double concentration_scale(const Case& c);
// The criterion of a case (time.steady_* keys).
SteadyCriterion steady_criterion(const Case& c);
// Bound on the remaining cold-start transient of the outlet section average at time t,
// relative to its steady value (condition 1 above).
double cold_start_transient(const Case& c, double t);

class SteadyStateDetector {
 public:
  explicit SteadyStateDetector(SteadyCriterion criterion) : crit_(criterion) {}

  // Record the probes at time t. Returns the change measure (infinity until two full
  // windows have been seen).
  double update(double t, const ProbeTable& p);
  bool steady() const { return steady_; }
  double t_steady() const { return t_steady_; }
  const SteadyCriterion& criterion() const { return crit_; }

  SteadySnapshot snapshot() const;
  void restore(const SteadySnapshot& s);

 private:
  // Mean of the samples with time in (t0, t1], per probe value.
  std::vector<double> window_mean(double t0, double t1) const;

  SteadyCriterion crit_;
  std::deque<std::pair<double, std::vector<double>>> samples_;  // (t, flattened profiles)
  bool steady_ = false;
  double t_steady_ = 0.0;
};

}  // namespace adrsph
