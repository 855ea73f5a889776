// High-order part of the advective face value (docs/benchmark.md, section 5: non-oscillatory at
// Pe = 1e5): C_face = C_i + slope_i / 2 with a TVD-limited slope; the part beyond
// first-order upwind is applied by deferred correction (steady_solver.cpp).
#include <algorithm>
#include <cmath>

#include "reference/finite_volume.hpp"

namespace adrsph::reference::detail {

double limited_slope(Limiter limiter, double dl, double dr) {
  if (limiter == Limiter::upwind || dl * dr <= 0.0) return 0.0;  // extremum: first order
  if (limiter == Limiter::minmod) return dl > 0.0 ? std::min(dl, dr) : std::max(dl, dr);
  return 2.0 * dl * dr / (dl + dr);  // van Leer: harmonic mean
}

void advective_correction(const Problem& p, const Grid& g, const std::vector<double>& u_cell,
                          Limiter limiter, const Eigen::VectorXd& c, Eigen::VectorXd& corr) {
  corr.setZero(g.cells());
  if (limiter == Limiter::upwind) return;
  const double dy = g.dy();
  // Faces i + 1/2 for i = 0 .. nx - 2; the outlet face has C_face = C_P (zero gradient).
  for (int i = 0; i + 1 < g.nx; ++i) {
    for (int j = 0; j < g.ny; ++j) {
      const double cp = c[g.index(i, j)];
      const double cw = i > 0 ? c[g.index(i - 1, j)] : 2.0 * p.inlet_value(g.yc(j)) - cp;
      const double ce = c[g.index(i + 1, j)];
      const double flux = u_cell[j] * dy * 0.5 * limited_slope(limiter, cp - cw, ce - cp);
      corr[g.index(i, j)] += flux;
      corr[g.index(i + 1, j)] -= flux;
    }
  }
}

}  // namespace adrsph::reference::detail
