#include "species/feed_integral.hpp"

#include <algorithm>
#include <limits>

#include "species/inlet_feed.hpp"

namespace adrsph {
namespace {

// Length of [a, b] ∩ [lo, hi].
double overlap(double a, double b, double lo, double hi) {
  return std::max(0.0, std::min(b, hi) - std::max(a, lo));
}

// int_a^b of the piecewise-linear table (held at its end values): the trapezoid rule is exact
// on each piece where the integrand is linear, so split [a, b] at the table's points.
double table_integral(const Case::Species& s, double a, double b) {
  const auto& tab = s.feed.table;
  double sum = 0.0, left = a;
  auto piece = [&](double right) {
    if (right <= left) return;
    sum += 0.5 * (right - left) * (inlet_concentration(s, left) + inlet_concentration(s, right));
    left = right;
  };
  for (const auto& point : tab)
    if (point[0] > a && point[0] < b) piece(point[0]);
  piece(b);
  return sum;
}

}  // namespace

double feed_integral(const Case::Species& s, double a, double b) {
  if (!(b > a)) return 0.0;
  const auto& f = s.feed;
  const double inf = std::numeric_limits<double>::infinity();
  switch (f.shape) {
    case FeedShape::constant:
      return s.c_in * (b - a);
    case FeedShape::step:
      return f.base * overlap(a, b, -inf, f.t0) + s.c_in * overlap(a, b, f.t0, inf);
    case FeedShape::pulse:
      return f.base * (b - a) + (s.c_in - f.base) * overlap(a, b, f.t0, f.t0 + f.width);
    case FeedShape::table:
      return table_integral(s, a, b);
  }
  return s.c_in * (b - a);
}

}  // namespace adrsph
