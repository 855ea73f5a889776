#include "species/inlet_feed.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace adrsph {

double inlet_concentration(const Case::Species& s, double t) {
  const auto& f = s.feed;
  switch (f.shape) {
    case FeedShape::constant:
      return s.c_in;
    case FeedShape::step:
      return t < f.t0 ? f.base : s.c_in;
    case FeedShape::pulse:
      return (t >= f.t0 && t < f.t0 + f.width) ? s.c_in : f.base;
    case FeedShape::table: {
      const auto& tab = f.table;
      if (t <= tab.front()[0]) return tab.front()[1];
      if (t >= tab.back()[0]) return tab.back()[1];
      const auto hi = std::upper_bound(tab.begin(), tab.end(), t,
                                       [](double v, const auto& p) { return v < p[0]; });
      const auto lo = hi - 1;
      const double w = (t - (*lo)[0]) / ((*hi)[0] - (*lo)[0]);
      return (*lo)[1] + w * ((*hi)[1] - (*lo)[1]);
    }
  }
  return s.c_in;
}

double feed_max(const Case::Species& s) {
  const auto& f = s.feed;
  switch (f.shape) {
    case FeedShape::constant:
      return s.c_in;
    case FeedShape::step:
    case FeedShape::pulse:
      return std::max(s.c_in, f.base);
    case FeedShape::table: {
      double m = 0.0;
      for (const auto& p : f.table) m = std::max(m, p[1]);
      return m;
    }
  }
  return s.c_in;
}

FeedMoments feed_moments(const Case::Species& s) {
  const auto& f = s.feed;
  FeedMoments m;
  if (f.shape == FeedShape::pulse) {
    // A rectangle of height c_in - base over [t0, t0 + width).
    m.amount = (s.c_in - f.base) * f.width;
    m.mean = f.t0 + 0.5 * f.width;
    m.variance = f.width * f.width / 12.0;
    return m;
  }
  if (f.shape != FeedShape::table) {
    m.amount = std::numeric_limits<double>::infinity();
    m.mean = m.variance = std::nan("");
    return m;
  }
  // Moments of the piecewise-linear excess g(t) = C(t) - base over the table's span (beyond
  // it the held end values count as the base): Simpson's rule per segment is exact for the
  // polynomials g, t g and t^2 g (at most cubic there).
  double m0 = 0.0, m1 = 0.0, m2 = 0.0;
  for (std::size_t i = 1; i < f.table.size(); ++i) {
    const double ta = f.table[i - 1][0], tb = f.table[i][0], h = tb - ta;
    const double ga = f.table[i - 1][1] - f.base, gb = f.table[i][1] - f.base;
    const double tm = 0.5 * (ta + tb), gm = 0.5 * (ga + gb);
    m0 += h / 6.0 * (ga + 4.0 * gm + gb);
    m1 += h / 6.0 * (ta * ga + 4.0 * tm * gm + tb * gb);
    m2 += h / 6.0 * (ta * ta * ga + 4.0 * tm * tm * gm + tb * tb * gb);
  }
  m.amount = m0;
  m.mean = m0 != 0.0 ? m1 / m0 : std::nan("");
  m.variance = m0 != 0.0 ? m2 / m0 - m.mean * m.mean : std::nan("");
  return m;
}

}  // namespace adrsph
