// Sampling the cell-centred field at probe points and section averages (docs/benchmark.md,
// section 4):
// linear between cell centres; between x = 0 and the first centre towards the Dirichlet
// inlet value; beyond the last centre (outlet) and the outermost rows (walls) the
// zero-gradient face value, i.e. the adjacent cell value.
#include <algorithm>
#include <cmath>

#include "adrsph/reference.hpp"

namespace adrsph::reference {
namespace {

// Bracketing centres for coordinate `s` measured from the first face, spacing h, n cells:
// value = (1 - w) * v[lo] + w * v[hi]. lo == -1 means "the face at s = 0" (inlet).
struct Bracket {
  int lo, hi;
  double w;
};

Bracket bracket_zero_gradient(double s, double h, int n) {
  const double t = s / h - 0.5;  // position in units of cells from the first centre
  if (t <= 0.0) return {0, 0, 0.0};
  if (t >= n - 1) return {n - 1, n - 1, 0.0};
  const int lo = std::min(static_cast<int>(std::floor(t)), n - 2);
  return {lo, lo + 1, t - lo};
}

Bracket bracket_x(double x, const Grid& g) {
  const double dx = g.dx();
  if (x < 0.5 * dx) return {-1, 0, std::max(x, 0.0) / (0.5 * dx)};  // from the inlet face
  return bracket_zero_gradient(x, dx, g.nx);
}

// Value of column i (i = -1: inlet face) on row j, or the column's section average.
double column_value(const Solution& s, const Problem& p, int i, int j) {
  return i < 0 ? p.inlet_value(s.grid.yc(j)) : s.at(i, j);
}

double column_average(const Solution& s, const Problem& p, int i) {
  double sum = 0.0;
  for (int j = 0; j < s.grid.ny; ++j) sum += column_value(s, p, i, j);
  return sum / s.grid.ny;  // sum_j C_ij dy / 2R
}

}  // namespace

double sample(const Solution& s, const Problem& p, double x, double y) {
  const Grid& g = s.grid;
  const Bracket bx = bracket_x(x, g);
  const Bracket by = bracket_zero_gradient(y + g.half_width, g.dy(), g.ny);
  auto row = [&](int j) {
    return (1.0 - bx.w) * column_value(s, p, bx.lo, j) + bx.w * column_value(s, p, bx.hi, j);
  };
  return (1.0 - by.w) * row(by.lo) + by.w * row(by.hi);
}

double section_average(const Solution& s, const Problem& p, double x) {
  const Bracket bx = bracket_x(x, s.grid);
  return (1.0 - bx.w) * column_average(s, p, bx.lo) + bx.w * column_average(s, p, bx.hi);
}

ProbeTable probe_table(const Solution& s, const Problem& p) {
  ProbeTable t;
  // The paper's r = +-2.5 mm for R = 5 (docs/benchmark.md, section 4).
  const double y_line = 0.5 * p.half_width;
  t.x_mm = probe_x_positions(p.length);
  for (double x : t.x_mm) {
    t.c_y0.push_back(sample(s, p, x, 0.0));
    t.c_yp25.push_back(sample(s, p, x, y_line));
    t.c_ym25.push_back(sample(s, p, x, -y_line));
    t.c_mean.push_back(section_average(s, p, x));
  }
  return t;
}

StationTable station_table(const Solution& s, const Problem& p) {
  StationTable t;
  t.x_mm = station_x_positions(p.length);
  for (double x : t.x_mm) t.c_mean.push_back(section_average(s, p, x));
  return t;
}

}  // namespace adrsph::reference
