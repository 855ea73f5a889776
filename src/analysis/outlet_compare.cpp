#include "analysis/outlet_compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "analysis/rtd.hpp"

namespace adrsph::analysis {
namespace {

struct Excursion {
  std::vector<double> t, e;
};

Excursion excursion(const std::vector<OutletRow>& rows) {
  Excursion x;
  for (const OutletRow& r : rows) {
    x.t.push_back(r.t);
    x.e.push_back(r.c_flow - rows.front().c_flow);
  }
  return x;
}

// Index of the largest |e|.
std::size_t peak_at(const std::vector<double>& e) {
  return static_cast<std::size_t>(
      std::max_element(e.begin(), e.end(),
                       [](double a, double b) { return std::abs(a) < std::abs(b); }) -
      e.begin());
}

double area(const std::vector<double>& t, const std::vector<double>& e) {
  double a = 0.0;
  for (std::size_t i = 1; i < t.size(); ++i) a += 0.5 * (t[i] - t[i - 1]) * (e[i] + e[i - 1]);
  return a;
}

}  // namespace

OutletSeriesError outlet_series_error(const std::string& species, const std::vector<OutletRow>& run,
                                      const std::vector<OutletRow>& ref) {
  if (run.size() < 3 || ref.size() < 3)
    throw std::invalid_argument("an outlet series needs at least 3 samples (run " +
                                std::to_string(run.size()) + ", reference " +
                                std::to_string(ref.size()) + ")");
  const double slack = 1e-9 * std::max(1.0, std::abs(run.back().t));
  if (std::abs(run.front().t) > slack || std::abs(ref.front().t) > slack ||
      ref.back().t < run.back().t - slack)
    throw std::invalid_argument(
        "the reference's outlet series covers t = " + rtd_number(ref.front().t) + " to " +
        rtd_number(ref.back().t) + " s, the run's " + rtd_number(run.front().t) + " to " +
        rtd_number(run.back().t) +
        " s: both must start at t = 0 and the reference must reach the run's last sample");
  const Excursion a = excursion(run), b = excursion(ref);
  std::vector<double> b_at(a.t.size());
  for (std::size_t i = 0; i < a.t.size(); ++i) b_at[i] = interpolate(b.t, b.e, a.t[i]);
  const std::vector<double> zero(a.t.size(), 0.0);
  const double ref_size = l1_distance(a.t, b_at, zero);
  if (!(ref_size > 0.0))
    throw std::invalid_argument(
        "the reference's outlet series does not move from its value at "
        "t = 0: nothing to compare");
  OutletSeriesError out;
  out.species = species;
  out.samples = a.t.size();
  out.run_area = area(a.t, a.e);
  out.ref_area = area(a.t, b_at);
  out.area_error = out.run_area / out.ref_area - 1.0;
  const std::size_t pa = peak_at(a.e), pb = peak_at(b.e);
  out.run_peak = a.e[pa];
  out.run_peak_t = a.t[pa];
  out.ref_peak = b.e[pb];
  out.ref_peak_t = b.t[pb];
  out.l1 = l1_distance(a.t, a.e, b_at) / ref_size;
  double worst = 0.0, size = 0.0;
  for (std::size_t i = 0; i < a.t.size(); ++i) {
    worst = std::max(worst, std::abs(a.e[i] - b_at[i]));
    size = std::max(size, std::abs(b_at[i]));
  }
  out.max_error = worst / size;
  const double ref_end = interpolate(b.t, b.e, a.t.back()) + ref.front().c_flow;
  if (std::abs(ref_end) > 1e-9 * std::max(std::abs(ref.front().c_flow), size))
    out.end_offset = run.back().c_flow / ref_end - 1.0;
  return out;
}

std::string outlet_compare_markdown(const std::string& run_name, const std::string& ref_name,
                                    const std::vector<OutletSeriesError>& rows) {
  std::string md = "# Outlet series: " + run_name + " against " + ref_name + "\n\n";
  md +=
      "e(t) = C_flow(t) - C_flow(0), the flow-weighted outlet mean's excursion from its start; "
      "the reference interpolated to the run's samples.\n\n";
  md +=
      "| species | samples | int e dt, run | reference | difference | peak e, run (t [s]) | "
      "reference (t [s]) | L1 | max | C_flow at the end, run / reference - 1 |\n"
      "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  char line[512], end[32];
  for (const OutletSeriesError& r : rows) {
    if (r.end_offset)
      std::snprintf(end, sizeof end, "%+.3f%%", 100.0 * *r.end_offset);
    else
      std::snprintf(end, sizeof end, "- (reference 0)");
    std::snprintf(line, sizeof line,
                  "| %s | %zu | %.6g | %.6g | %+.2f%% | %.5g (%.3g) | %.5g (%.3g) | %.2f%% | "
                  "%.2f%% | %s |\n",
                  r.species.empty() ? "-" : r.species.c_str(), r.samples, r.run_area, r.ref_area,
                  100.0 * r.area_error, r.run_peak, r.run_peak_t, r.ref_peak, r.ref_peak_t,
                  100.0 * r.l1, 100.0 * r.max_error, end);
    md += line;
  }
  return md;
}

}  // namespace adrsph::analysis
