// Steady state: the probe profiles stop changing. Single snapshots carry sampling noise
// (rows of particles slide past the probe points), so the test compares the MEAN probe
// profiles over two consecutive windows [t - 2w, t - w] and [t - w, t], sampled at jittered
// instants (see simulation.cpp). The run is steady when the largest change of any probe's
// window mean, relative to the inlet concentration, is below the tolerance. The particle
// noise of the window means sets a floor: about 1e-4..1e-3 here, so tolerances below
// 1e-4 may never be met.
#pragma once

#include <algorithm>
#include <cmath>
#include <deque>

#include "adrsph/probes.hpp"

namespace adrsph {

class SteadyStateDetector {
 public:
  SteadyStateDetector(double tol, double window, double scale)
      : tol_(tol), window_(window), scale_(scale) {}

  // Record the probes at time t. Returns the change measure (infinity until two full
  // windows have been seen).
  double update(double t, const ProbeTable& p);
  bool steady() const { return steady_; }
  double t_steady() const { return t_steady_; }

 private:
  // Mean of the samples with time in (t0, t1], per probe value.
  std::vector<double> window_mean(double t0, double t1) const;

  double tol_, window_, scale_;
  std::deque<std::pair<double, std::vector<double>>> samples_;  // (t, flattened profiles)
  bool steady_ = false;
  double t_steady_ = 0.0;
};

}  // namespace adrsph
