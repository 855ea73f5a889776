// Grid convergence measures (docs/benchmark.md, section 5: the change of every section
// average between the two finest grids must be below 1e-4 relative).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

#include "adrsph/reference.hpp"

namespace adrsph::reference {

double relative_change(const std::vector<ConvergenceLevel>& levels, std::size_t l, std::size_t m) {
  const double f1 = levels[l].stations.c_mean[m], f0 = levels[l - 1].stations.c_mean[m];
  return std::abs(f1 - f0) / std::abs(f1);
}

double observed_order(const std::vector<ConvergenceLevel>& levels, std::size_t l, std::size_t m) {
  const double f0 = levels[l - 2].stations.c_mean[m];
  const double f1 = levels[l - 1].stations.c_mean[m];
  const double f2 = levels[l].stations.c_mean[m];
  const double d01 = std::abs(f1 - f0), d12 = std::abs(f2 - f1);
  if (d01 == 0.0 || d12 == 0.0) return std::numeric_limits<double>::quiet_NaN();
  return std::log2(d01 / d12);
}

}  // namespace adrsph::reference

namespace adrsph::reference {

ConvergenceVerdict convergence_verdict(const std::vector<ConvergenceLevel>& levels, int nx,
                                       double tolerance) {
  ConvergenceVerdict v;
  for (std::size_t l = 0; l + 1 < levels.size(); ++l) {
    if (levels[l].nx != nx) continue;
    v.checked = true;
    for (std::size_t m = 0; m < levels[l].stations.c_mean.size(); ++m)
      v.max_change = std::max(v.max_change, relative_change(levels, l + 1, m));
    v.pass = v.max_change < tolerance;
  }
  return v;
}

std::string convergence_table(const std::vector<ConvergenceLevel>& levels) {
  if (levels.empty()) return {};
  const auto& xs = levels.front().stations.x_mm;
  char buf[96];
  std::string head = "| grid | solve s |", rule = "|---|---|";
  for (double x : xs) {
    std::snprintf(buf, sizeof buf, " C_mean x=%g | rel. change | order p |", x);
    head += buf;
    rule += "---|---|---|";
  }
  std::string out = head + "\n" + rule + "\n";
  for (std::size_t l = 0; l < levels.size(); ++l) {
    const ConvergenceLevel& lv = levels[l];
    std::snprintf(buf, sizeof buf, "| %dx%d | %.2f |", lv.nx, lv.ny,
                  lv.report.assembly_seconds + lv.report.solve_seconds);
    out += buf;
    for (std::size_t m = 0; m < xs.size(); ++m) {
      std::snprintf(buf, sizeof buf, " %.8f |", lv.stations.c_mean[m]);
      out += buf;
      if (l >= 1)
        std::snprintf(buf, sizeof buf, " %.2e |", relative_change(levels, l, m));
      else
        std::snprintf(buf, sizeof buf, " - |");
      out += buf;
      if (l >= 2)
        std::snprintf(buf, sizeof buf, " %.2f |", observed_order(levels, l, m));
      else
        std::snprintf(buf, sizeof buf, " - |");
      out += buf;
    }
    out += "\n";
  }
  return out;
}

}  // namespace adrsph::reference
