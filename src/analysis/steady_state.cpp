#include "analysis/steady_state.hpp"

#include <array>
#include <limits>

#include "species/reaction_kinetics.hpp"

namespace adrsph {

namespace {
std::vector<double> flatten(const ProbeTable& p) {
  std::vector<double> v;
  v.reserve(4 * p.x_mm.size());
  for (const auto* a : {&p.c_y0, &p.c_yp25, &p.c_ym25, &p.c_mean})
    v.insert(v.end(), a->begin(), a->end());
  return v;
}
// C(tau) of a batch of the case's kinetics from c0 (reaction_kinetics.hpp), tabulated on
// log-spaced tau from 1e-6 s to 1e6 s and interpolated: the bound below needs it for every
// streamline's residence time L / u(y), arbitrarily long near the walls.
class BatchTable {
 public:
  BatchTable(const Case& c, double c0) {
    double conc = c0, tau = 0.0;
    for (int i = 0; i < kPoints; ++i) {
      const double next = kTau0 * std::pow(kRatio, i);
      conc = batch_concentration(c, conc, next - tau);
      tau = next;
      values_[i] = conc;
    }
    c0_ = c0;
  }
  double operator()(double tau) const {
    if (tau <= kTau0) return c0_ + (values_[0] - c0_) * tau / kTau0;
    const double s = std::log(tau / kTau0) / std::log(kRatio);
    if (s >= kPoints - 1) return values_[kPoints - 1];
    const int i = static_cast<int>(s);
    return values_[i] + (s - i) * (values_[i + 1] - values_[i]);
  }

 private:
  static constexpr int kPoints = 1201;
  static constexpr double kTau0 = 1e-6;
  static constexpr double kRatio = 1.023292992280754;  // 10^(12 / 1200): 1e-6 .. 1e6 s
  std::array<double, kPoints> values_{};
  double c0_ = 0.0;
};

// The bound of a case with [[reaction]] tables, its batch tables built once.
class KineticsBound {
 public:
  explicit KineticsBound(const Case& c)
      : c_(c),
        c_init_(c.species.feed.shape == FeedShape::step &&
                        std::fabs(c.species.feed.base - c.species.c_in) >
                            std::fabs(c.species.c_init - c.species.c_in)
                    ? c.species.feed.base
                    : c.species.c_init),
        from_inlet_(c, c.species.c_in),
        from_initial_(c, c_init_) {}

  // Condition 1 of steady_state.hpp for any kinetics, with the batch solution B(tau; c0) in
  // place of c0 exp(-k tau): an unswept streamline holds B(t; c_init) instead of its steady
  // B(L/u; c_in), and |B(t; c_init) - B(L/u; c_in)| <= |B(t; c_init) - B(t; c_in)|
  // + B(t; c_in) - B(L/u; c_in) (B decreases in tau: reactions only consume). The zones of
  // [[reaction]] tables are left out (factor 1 everywhere).
  double operator()(double t) const {
    const double L = c_.geometry.length, u_max = c_.u_max(), c_in = c_.species.c_in;
    constexpr int n = 4000;
    double steady = 0.0, excess = 0.0;
    const double b_in = from_inlet_(t), b_init = from_initial_(t);
    for (int i = 0; i < n; ++i) {
      const double eta = (i + 0.5) / n;
      const double u = u_max * (1.0 - eta * eta);
      const double c_steady = from_inlet_(L / u);
      steady += c_steady;
      if (u * t < L) excess += std::fabs(b_init - b_in) + (b_in - c_steady);
    }
    return excess / std::max(steady, 1e-12 * std::max(c_in, 1e-300));
  }

 private:
  const Case& c_;
  double c_init_;
  BatchTable from_inlet_, from_initial_;
};

}  // namespace

double cold_start_transient(const Case& c, double t) {
  if (!c.reactions.empty()) return KineticsBound(c)(t);
  const double L = c.geometry.length, u_max = c.u_max();
  const double k = c.species.k, c_in = c.species.c_in;
  // A step feed sweeps away whichever of the initial fluid and the pre-step feed is farther
  // from c_in (steady_state.hpp, condition 1).
  const double c_init =
      c.species.feed.shape == FeedShape::step &&
              std::fabs(c.species.feed.base - c_in) > std::fabs(c.species.c_init - c_in)
          ? c.species.feed.base
          : c.species.c_init;
  // Midpoint rule over y in [0, R] (the profile is symmetric); 4000 points resolve the
  // near-wall layer where the unswept streamlines are.
  constexpr int n = 4000;
  double steady = 0.0, excess = 0.0;
  for (int i = 0; i < n; ++i) {
    const double eta = (i + 0.5) / n;
    const double u = u_max * (1.0 - eta * eta);
    const double c_steady = c_in * std::exp(-k * L / u);
    steady += c_steady;
    // Not yet swept at the outlet (u t < L): this streamline still holds the initial fluid.
    if (u * t < L)
      excess += std::fabs(c_init - c_in) * std::exp(-k * t) + (c_in * std::exp(-k * t) - c_steady);
  }
  return excess / std::max(steady, 1e-12 * std::max(c_in, 1e-300));
}

SteadyCriterion steady_criterion(const Case& c) {
  SteadyCriterion s;
  s.tol = c.time.steady_tol;
  s.window = c.time.steady_window;
  s.scale = std::max(c.species.c_in, 1e-300);
  // The earliest time the bound on the cold-start transient allows (it only decreases).
  s.t_min = 0.0;
  if (c.time.steady_sweep_tol > 0.0) {
    const double step = 0.01;
    if (c.reactions.empty()) {
      while (s.t_min < c.time.t_end && cold_start_transient(c, s.t_min) > c.time.steady_sweep_tol)
        s.t_min += step;
    } else {
      const KineticsBound bound(c);
      while (s.t_min < c.time.t_end && bound(s.t_min) > c.time.steady_sweep_tol) s.t_min += step;
    }
  }
  if (c.species.feed.shape == FeedShape::step) s.t_min += c.species.feed.t0;
  return s;
}

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
  const double w = crit_.window;
  const double eps = 1e-9 * w;
  samples_.emplace_back(t, flatten(p));
  while (!samples_.empty() && samples_.front().first < t - 2.0 * w - eps) samples_.pop_front();
  if (t < 2.0 * w - eps) return std::numeric_limits<double>::infinity();  // too early
  const auto recent = window_mean(t - w - eps, t + eps);
  const auto earlier = window_mean(t - 2.0 * w - eps, t - w - eps);
  if (recent.empty() || earlier.empty()) return std::numeric_limits<double>::infinity();
  double change = 0.0;
  for (std::size_t i = 0; i < recent.size(); ++i)
    change = std::max(change, std::fabs(recent[i] - earlier[i]));
  change /= crit_.scale;
  if (change < crit_.tol && t >= crit_.t_min && !steady_) {
    steady_ = true;
    t_steady_ = t;
  }
  return change;
}

SteadySnapshot SteadyStateDetector::snapshot() const {
  SteadySnapshot s;
  for (const auto& [t, v] : samples_) {
    s.t.push_back(t);
    s.values.push_back(v);
  }
  s.steady = steady_;
  s.t_steady = t_steady_;
  return s;
}

void SteadyStateDetector::restore(const SteadySnapshot& s) {
  samples_.clear();
  for (std::size_t i = 0; i < s.t.size() && i < s.values.size(); ++i)
    samples_.emplace_back(s.t[i], s.values[i]);
  steady_ = s.steady;
  t_steady_ = s.t_steady;
}

}  // namespace adrsph
