// Steady state: the probe profiles stop changing. At every check the largest change of any
// probe value since the previous check, relative to the inlet concentration, is compared with
// the tolerance; the run is steady once it stayed below for the whole window.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>

#include "adrsph/probes.hpp"

namespace adrsph {

class SteadyStateDetector {
 public:
  SteadyStateDetector(double tol, double window, double scale)
      : tol_(tol), window_(window), scale_(scale) {}

  // Returns the change measure of this check (0 for the first one).
  double update(double t, const ProbeTable& p) {
    double change = 0.0;
    if (prev_) {
      auto diff = [&](const std::vector<double>& a, const std::vector<double>& b) {
        for (std::size_t i = 0; i < a.size(); ++i) change = std::max(change, std::fabs(a[i] - b[i]));
      };
      diff(p.c_y0, prev_->c_y0);
      diff(p.c_yp25, prev_->c_yp25);
      diff(p.c_ym25, prev_->c_ym25);
      diff(p.c_mean, prev_->c_mean);
      change /= scale_;
      if (!(change < tol_)) below_since_.reset();
      else if (!below_since_) below_since_ = t_prev_;
      if (below_since_ && !steady_ && t - *below_since_ >= window_ - 1e-12) {
        steady_ = true;
        t_steady_ = t;
      }
    }
    prev_ = p;
    t_prev_ = t;
    return change;
  }
  bool steady() const { return steady_; }
  double t_steady() const { return t_steady_; }

 private:
  double tol_, window_, scale_;
  std::optional<ProbeTable> prev_;
  double t_prev_ = 0.0;
  std::optional<double> below_since_;
  bool steady_ = false;
  double t_steady_ = 0.0;
};

}  // namespace adrsph
