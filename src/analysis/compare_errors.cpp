// Relative errors of a run against the reference (docs/benchmark.md, section 4; the paper's
// figures 3-5 and table 3): |C - C_ref| / C_ref.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "analysis/compare.hpp"

namespace adrsph::analysis {
namespace {

double relative_error(double c, double c_ref) {
  if (!(c_ref > 0.0))
    throw std::runtime_error("compare: reference C <= 0 (" + std::to_string(c_ref) +
                             "): relative error undefined");
  return std::abs(c - c_ref) / c_ref;
}

// Linear interpolation of column `v` of the reference at `x` (xs ascending).
double interpolate(const std::vector<double>& xs, const std::vector<double>& v, double x) {
  constexpr double kSnap = 1e-9;
  const auto it = std::lower_bound(xs.begin(), xs.end(), x - kSnap);
  if (it == xs.end() || (it == xs.begin() && x < xs.front() - kSnap))
    throw std::runtime_error("compare: run probe x = " + std::to_string(x) +
                             " mm lies outside the reference probes");
  const std::size_t i = static_cast<std::size_t>(it - xs.begin());
  if (std::abs(xs[i] - x) <= kSnap) return v[i];
  const double w = (x - xs[i - 1]) / (xs[i] - xs[i - 1]);
  return (1.0 - w) * v[i - 1] + w * v[i];
}

}  // namespace

LineErrors line_errors(const ProbeTable& run, const ProbeTable& ref) {
  if (ref.x_mm.empty()) throw std::runtime_error("compare: the reference has no probes");
  LineErrors e;
  for (std::size_t i = 0; i < run.x_mm.size(); ++i) {
    const double x = run.x_mm[i];
    e.x_mm.push_back(x);
    e.err_y0.push_back(relative_error(run.c_y0[i], interpolate(ref.x_mm, ref.c_y0, x)));
    e.err_yp25.push_back(relative_error(run.c_yp25[i], interpolate(ref.x_mm, ref.c_yp25, x)));
    e.err_ym25.push_back(relative_error(run.c_ym25[i], interpolate(ref.x_mm, ref.c_ym25, x)));
    e.err_mean.push_back(relative_error(run.c_mean[i], interpolate(ref.x_mm, ref.c_mean, x)));
  }
  return e;
}

std::vector<LineSummary> summarise(const LineErrors& e) {
  const std::pair<const char*, const std::vector<double>*> cols[] = {
      {"y = 0", &e.err_y0},
      {"y = +2.5", &e.err_yp25},
      {"y = -2.5", &e.err_ym25},
      {"section average", &e.err_mean}};
  std::vector<LineSummary> out;
  for (const auto& [name, v] : cols) {
    LineSummary s{name};
    for (double x : *v) {
      s.max = std::max(s.max, x);
      s.mean += x;
    }
    if (!v->empty()) s.mean /= static_cast<double>(v->size());
    out.push_back(s);
  }
  return out;
}

std::vector<StationError> station_errors(const StationTable& run, const StationTable& ref,
                                         std::optional<double> pe) {
  const std::optional<PaperRow> paper = pe ? paper_table3_row(*pe) : std::nullopt;
  std::vector<StationError> out;
  for (std::size_t i = 0; i < run.x_mm.size(); ++i) {
    const double x = run.x_mm[i];
    const double c_ref = interpolate(ref.x_mm, ref.c_mean, x);
    StationError s{x, run.c_mean[i], c_ref, relative_error(run.c_mean[i], c_ref), {}, {}};
    if (paper && i < 3) {  // table 3 columns are x = 25, 50, 100 (scaled with L)
      s.paper_modern = paper->modern[i];
      s.paper_conventional = paper->conventional[i];
    }
    out.push_back(s);
  }
  return out;
}

}  // namespace adrsph::analysis
