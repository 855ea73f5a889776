#include "analysis/rtd.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

namespace adrsph::analysis {
std::string rtd_number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// The analysis needs a feed of finite amount whose moments feed_moments() gives exactly.
void check_rtd_feed(const Case& c) {
  const auto& f = c.species.feed;
  if (f.shape != FeedShape::pulse && f.shape != FeedShape::table)
    throw RtdInputError(RtdInputError::Source::feed,
                        std::string("RTD needs species.feed.shape = \"pulse\" or \"table\" (a "
                                    "tracer input of finite amount), got \"") +
                            to_string(f.shape) +
                            "\"; run the case again with, e.g., --set species.feed.shape=pulse "
                            "--set species.feed.width=0.05");
  if (f.shape == FeedShape::table) {
    // Beyond its ends the inlet holds the end values; the excess is finite (and its moments
    // those of feed_moments()) only if both are the base.
    const double scale = std::max(1.0, feed_max(c.species));
    for (const auto& end : {f.table.front(), f.table.back()})
      if (std::abs(end[1] - f.base) > 1e-9 * scale)
        throw RtdInputError(
            RtdInputError::Source::feed,
            "species.feed.table must start and end at species.feed.base = " + rtd_number(f.base) +
                " (a finite tracer input), got C = " + rtd_number(end[1]) + " at t = " +
                rtd_number(end[0]) + "; add points at the base before and after the input");
  }
  const FeedMoments m = feed_moments(c.species);
  if (!(std::abs(m.amount) > 0.0) || !std::isfinite(m.amount))
    throw RtdInputError(RtdInputError::Source::feed,
                        "the feed carries no tracer (its excess over species.feed.base = " +
                            rtd_number(f.base) + " has amount " + rtd_number(m.amount) +
                            "); set species.c_in (or the table) apart from the base");
}

CurveMoments curve_moments(const std::vector<double>& t, const std::vector<double>& g) {
  CurveMoments m;
  double first = 0.0;
  for (std::size_t i = 1; i < t.size(); ++i) {
    const double h = t[i] - t[i - 1];
    m.area += 0.5 * h * (g[i - 1] + g[i]);
    first += 0.5 * h * (t[i - 1] * g[i - 1] + t[i] * g[i]);
  }
  m.mean = first / m.area;
  // The central second moment directly (not int t^2 g / area - mean^2, which cancels badly
  // when the spread is small beside the mean).
  double second = 0.0;
  for (std::size_t i = 1; i < t.size(); ++i) {
    const double da = t[i - 1] - m.mean, db = t[i] - m.mean;
    second += 0.5 * (t[i] - t[i - 1]) * (da * da * g[i - 1] + db * db * g[i]);
  }
  m.variance = second / m.area;
  return m;
}

double l1_distance(const std::vector<double>& t, const std::vector<double>& a,
                   const std::vector<double>& b) {
  double sum = 0.0;
  for (std::size_t i = 1; i < t.size(); ++i)
    sum += 0.5 * (t[i] - t[i - 1]) * (std::abs(a[i - 1] - b[i - 1]) + std::abs(a[i] - b[i]));
  return sum;
}

double interpolate(const std::vector<double>& t, const std::vector<double>& v, double at) {
  const auto hi = std::upper_bound(t.begin(), t.end(), at);
  if (hi == t.begin()) return v.front();
  if (hi == t.end()) return v.back();
  const std::size_t i = static_cast<std::size_t>(hi - t.begin());
  const double w = (at - t[i - 1]) / (t[i] - t[i - 1]);
  return v[i - 1] + w * (v[i] - v[i - 1]);
}

Rtd residence_time_distribution(const std::vector<OutletRow>& rows, const Case& c) {
  Rtd r;
  check_rtd_feed(c);
  r.feed = feed_moments(c.species);
  if (rows.size() < 3)
    throw RtdInputError(RtdInputError::Source::outlet,
                        std::to_string(rows.size()) + (rows.size() == 1 ? " sample" : " samples") +
                            ", the moments need at least 3; sample more often "
                            "(output.outlet_interval) or run longer (time.t_end)");
  const double base = c.species.feed.base;
  std::vector<double> g;
  for (const OutletRow& row : rows) {
    r.t.push_back(row.t);
    r.c_out.push_back(row.c_flow);
    g.push_back(row.c_flow - base);
  }
  r.outlet = curve_moments(r.t, g);
  // The excess has the feed's sign (a dip below the base is a tracer input too); "zero" is
  // relative to the feed's amount, as noise leaves a tiny area where no pulse arrived.
  const double sign = r.feed.amount > 0.0 ? 1.0 : -1.0;
  if (!(sign * r.outlet.area > 1e-12 * std::abs(r.feed.amount)))
    throw RtdInputError(RtdInputError::Source::outlet,
                        "the outlet's excess over species.feed.base = " + rtd_number(base) +
                            " has zero area (area " + rtd_number(r.outlet.area) +
                            "): the tracer has not reached the outlet; run longer (time.t_end)");

  for (double v : g) r.e_out.push_back(v / r.outlet.area);
  r.mean_residence_time = r.outlet.mean - r.feed.mean;
  r.variance = r.outlet.variance - r.feed.variance;
  r.mean_velocity = mean_velocity(c);
  r.space_time = c.geometry.length / r.mean_velocity;
  r.recovery = r.outlet.area / r.feed.amount;
  double peak = 0.0;
  for (double v : g) peak = std::max(peak, sign * v);
  r.tail = sign * g.back() / peak;
  r.truncated = r.tail > Rtd::kTruncatedTail;

  r.has_model = c.species.D > 0.0;
  if (!r.has_model) {
    const double nan = std::nan("");
    r.model = {nan, nan, r.space_time, 0.0, {nan, nan}};
    r.model_area = r.l1 = nan;
    r.closed_mean = r.closed_variance = r.closed_l1 = nan;
    r.c_model.assign(r.t.size(), nan);
    r.c_closed.assign(r.t.size(), nan);
    return r;
  }
  r.model = taylor_aris(c);
  std::vector<double> g_model;
  for (double t : r.t) g_model.push_back(model_outlet_excess(c.species, r.model.residence, t));
  for (double v : g_model) r.c_model.push_back(base + v);
  // The model normalised on the same samples as the measurement, so that both integrate to 1
  // under the same rule and the L1 distance compares shapes only.
  r.model_area = curve_moments(r.t, g_model).area;
  std::vector<double> e_model;
  for (double v : g_model) e_model.push_back(v / r.model_area);
  r.l1 = l1_distance(r.t, r.e_out, e_model);

  const std::vector<double> g_closed = closed_outlet_excess(c, r.model, r.t);
  for (double v : g_closed) r.c_closed.push_back(base + v);
  const CurveMoments closed = curve_moments(r.t, g_closed);
  r.closed_mean = closed.mean - r.feed.mean;
  r.closed_variance = closed.variance - r.feed.variance;
  std::vector<double> e_closed;
  for (double v : g_closed) e_closed.push_back(v / closed.area);
  r.closed_l1 = l1_distance(r.t, r.e_out, e_closed);
  return r;
}

}  // namespace adrsph::analysis
