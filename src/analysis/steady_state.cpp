#include "analysis/steady_state.hpp"

#include <limits>

namespace adrsph {

namespace {
std::vector<double> flatten(const ProbeTable& p) {
  std::vector<double> v;
  v.reserve(4 * p.x_mm.size());
  for (const auto* a : {&p.c_y0, &p.c_yp25, &p.c_ym25, &p.c_mean}) v.insert(v.end(), a->begin(), a->end());
  return v;
}
}  // namespace

std::vector<double> SteadyStateDetector::window_mean(double t0, double t1) const {
  std::vector<double> mean;
  int count = 0;
  for (const auto& [t, v] : samples_) {
    if (t <= t0 || t > t1) continue;
    if (mean.empty()) mean.assign(v.size(), 0.0);
    for (std::size_t i = 0; i < v.size(); ++i) mean[i] += v[i];
    ++count;
  }
  for (double& m : mean) m /= std::max(count, 1);
  return mean;
}

double SteadyStateDetector::update(double t, const ProbeTable& p) {
  const double eps = 1e-9 * window_;
  samples_.emplace_back(t, flatten(p));
  while (!samples_.empty() && samples_.front().first < t - 2.0 * window_ - eps) samples_.pop_front();
  if (t < 2.0 * window_ - eps) return std::numeric_limits<double>::infinity();  // too early
  const auto recent = window_mean(t - window_ - eps, t + eps);
  const auto earlier = window_mean(t - 2.0 * window_ - eps, t - window_ - eps);
  if (recent.empty() || earlier.empty()) return std::numeric_limits<double>::infinity();
  double change = 0.0;
  for (std::size_t i = 0; i < recent.size(); ++i)
    change = std::max(change, std::fabs(recent[i] - earlier[i]));
  change /= scale_;
  if (change < tol_ && !steady_) {
    steady_ = true;
    t_steady_ = t;
  }
  return change;
}

}  // namespace adrsph
