#include "analysis/rtd_against.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace adrsph::analysis {
namespace {

// The physical keys that shape the outlet response: the two cases should agree on them.
std::vector<std::string> differences(const Case& run, const Case& ref) {
  std::vector<std::string> out;
  auto key = [&out](const char* name, double a, double b) {
    if (a != b)
      out.push_back(std::string(name) + ": run " + rtd_number(a) + ", reference " + rtd_number(b));
  };
  key("geometry.length", run.geometry.length, ref.geometry.length);
  key("geometry.half_width", run.geometry.half_width, ref.geometry.half_width);
  key("fluid.u_bulk", run.fluid.u_bulk, ref.fluid.u_bulk);
  key("species.D", run.species.D, ref.species.D);
  key("species.k", run.species.k, ref.species.k);
  key("species.c_in", run.species.c_in, ref.species.c_in);
  key("species.c_init", run.species.c_init, ref.species.c_init);
  const auto &f = run.species.feed, &g = ref.species.feed;
  if (f.shape != g.shape)
    out.push_back(std::string("species.feed.shape: run ") + to_string(f.shape) + ", reference " +
                  to_string(g.shape));
  key("species.feed.t0", f.t0, g.t0);
  key("species.feed.width", f.width, g.width);
  key("species.feed.base", f.base, g.base);
  if (f.table != g.table) out.push_back("species.feed.table: the two tables differ");
  return out;
}

}  // namespace

RtdAgainst against_reference(const Rtd& run, const Case& run_case,
                             const std::vector<OutletRow>& reference, const Case& reference_case) {
  using Source = RtdInputError::Source;
  RtdAgainst a;
  a.samples = reference.size();
  if (reference.size() < 3)
    throw RtdInputError(Source::outlet, std::to_string(reference.size()) +
                                            " samples, the reference's moments need at least 3");
  a.t_first = reference.front().t;
  a.t_last = reference.back().t;
  // Covering: the run's first and last samples lie within the reference's (to rounding).
  const double slack = 1e-9 * std::max({1.0, std::abs(run.t.front()), std::abs(run.t.back())});
  if (a.t_first > run.t.front() + slack || a.t_last < run.t.back() - slack)
    throw RtdInputError(
        Source::outlet,
        "the reference's samples cover t = " + rtd_number(a.t_first) + " to " +
            rtd_number(a.t_last) + " s, not the run's t = " + rtd_number(run.t.front()) + " to " +
            rtd_number(run.t.back()) +
            " s; solve the reference to time.t_end >= " + rtd_number(run.t.back()) + " s");

  a.feed = feed_moments(reference_case.species);
  const double base = reference_case.species.feed.base;
  std::vector<double> t, g;
  for (const OutletRow& row : reference) {
    t.push_back(row.t);
    g.push_back(row.c_flow - base);
  }
  a.outlet = curve_moments(t, g);
  const double sign = a.feed.amount > 0.0 ? 1.0 : -1.0;
  if (!(sign * a.outlet.area > 1e-12 * std::abs(a.feed.amount)))
    throw RtdInputError(Source::outlet,
                        "the reference's excess over species.feed.base = " + rtd_number(base) +
                            " has zero area (area " + rtd_number(a.outlet.area) + ")");
  a.mean_residence_time = a.outlet.mean - a.feed.mean;
  a.variance = a.outlet.variance - a.feed.variance;
  a.recovery = a.outlet.area / a.feed.amount;

  for (double at : run.t) {
    const double v = interpolate(t, g, at);
    a.c_ref.push_back(base + v);
    a.e_ref.push_back(v / a.outlet.area);
  }
  a.l1 = l1_distance(run.t, run.e_out, a.e_ref);
  a.mean_over_reference_minus_1 = run.mean_residence_time / a.mean_residence_time - 1.0;
  a.variance_over_reference_minus_1 = run.variance / a.variance - 1.0;
  a.case_differences = differences(run_case, reference_case);
  return a;
}

}  // namespace adrsph::analysis
