#include "analysis/steady_state.hpp"

#include <algorithm>
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
// The residence times at which the bounds below tabulate a batch of the case's kinetics:
// log-spaced from 1e-6 s to 1e6 s, since every streamline's residence time L / u(y) is needed,
// arbitrarily long near the walls.
struct TauGrid {
  static constexpr int kPoints = 1201;
  static constexpr double kTau0 = 1e-6;
  static constexpr double kRatio = 1.023292992280754;  // 10^(12 / 1200): 1e-6 .. 1e6 s
  static double grid_tau(int i) { return kTau0 * std::pow(kRatio, i); }
};

// C(tau) of a batch of the case's kinetics from c0 (reaction_kinetics.hpp) on TauGrid,
// interpolated linearly in log tau.
class BatchTable : TauGrid {
 public:
  BatchTable(const Case& c, double c0) {
    double conc = c0, tau = 0.0;
    for (int i = 0; i < kPoints; ++i) {
      const double next = grid_tau(i);
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

// The same bound for a network of several species (steady_state.hpp, condition 1): the batch
// state B(tau) of all species together (batch_state), from the inlet values and from the
// initial ones, tabulated on TauGrid (and tau = 0). A product need not decrease
// in tau, so the second term is |B(t; in) - B(L/u; in)|. Each species' bound is relative to
// its steady outlet section average, or to 1% of the concentration scale for a species that
// leaves with less; the largest over the species counts.
class NetworkBound : TauGrid {
 public:
  explicit NetworkBound(const Case& c)
      : c_(c), zone_free_(without_zones(c)), scale_(concentration_scale(c)) {
    std::vector<double> in, init;
    for (int s = 0; s < c.species_count(); ++s) {
      in.push_back(c.species_at(s).c_in);
      init.push_back(c.species_at(s).c_init);
    }
    double tau = 0.0;
    from_inlet_.push_back(in);
    from_initial_.push_back(init);
    taus_.push_back(0.0);
    for (int i = 0; i < kPoints; ++i) {
      const double next = grid_tau(i);
      in = batch_state(zone_free_, in, next - tau);
      init = batch_state(zone_free_, init, next - tau);
      tau = next;
      taus_.push_back(tau);
      from_inlet_.push_back(in);
      from_initial_.push_back(init);
    }
  }
  double operator()(double t) const {
    const double L = c_.geometry.length, u_max = c_.u_max();
    constexpr int n = 4000;
    double worst = 0.0;
    for (int s = 0; s < c_.species_count(); ++s) {
      double steady = 0.0, excess = 0.0;
      const double b_in = at(from_inlet_, t, s), b_init = at(from_initial_, t, s);
      for (int i = 0; i < n; ++i) {
        const double eta = (i + 0.5) / n;
        const double u = u_max * (1.0 - eta * eta);
        const double c_steady = at(from_inlet_, L / u, s);
        steady += c_steady;
        if (u * t < L) excess += std::fabs(b_init - b_in) + std::fabs(b_in - c_steady);
      }
      worst = std::max(worst, excess / std::max(steady, 1e-2 * scale_ * n));
    }
    return worst;
  }

 private:
  // Linear in tau between the tabulated points, the last value beyond them.
  double at(const std::vector<std::vector<double>>& table, double tau, int s) const {
    const auto it = std::upper_bound(taus_.begin(), taus_.end(), tau);
    if (it == taus_.end()) return table.back()[static_cast<std::size_t>(s)];
    const std::size_t i = static_cast<std::size_t>(it - taus_.begin());
    const double w = (tau - taus_[i - 1]) / (taus_[i] - taus_[i - 1]);
    return table[i - 1][static_cast<std::size_t>(s)] +
           w * (table[i][static_cast<std::size_t>(s)] - table[i - 1][static_cast<std::size_t>(s)]);
  }
  // The case with the zones of its [[reaction]] tables left out (factor 1 everywhere), copied
  // once for the 2 x 1201 batch steps.
  static Case without_zones(const Case& c) {
    Case plain = c;
    for (Reaction& r : plain.reactions) r.zones.clear();
    return plain;
  }
  const Case& c_;
  Case zone_free_;
  double scale_;
  std::vector<double> taus_;
  std::vector<std::vector<double>> from_inlet_, from_initial_;
};

}  // namespace

double concentration_scale(const Case& c) {
  double scale = 0.0;
  for (int s = 0; s < c.species_count(); ++s) scale = std::max(scale, c.species_at(s).c_in);
  return std::max(scale, 1e-300);
}

double cold_start_transient(const Case& c, double t) {
  if (c.species_count() > 1) return NetworkBound(c)(t);
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
  s.scale = concentration_scale(c);
  // The earliest time the bound on the cold-start transient allows (it only decreases).
  s.t_min = 0.0;
  if (c.time.steady_sweep_tol > 0.0) {
    const double step = 0.01;
    if (c.species_count() > 1) {
      const NetworkBound bound(c);
      while (s.t_min < c.time.t_end && bound(s.t_min) > c.time.steady_sweep_tol) s.t_min += step;
    } else if (c.reactions.empty()) {
      while (s.t_min < c.time.t_end && cold_start_transient(c, s.t_min) > c.time.steady_sweep_tol)
        s.t_min += step;
    } else {
      const KineticsBound bound(c);
      while (s.t_min < c.time.t_end && bound(s.t_min) > c.time.steady_sweep_tol) s.t_min += step;
    }
  }
  double t_step = 0.0;  // the latest step of a species' feed starts the sweep
  for (int sp = 0; sp < c.species_count(); ++sp)
    if (c.species_at(sp).feed.shape == FeedShape::step)
      t_step = std::max(t_step, c.species_at(sp).feed.t0);
  s.t_min += t_step;
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
