#include "neighbours/displacement_monitor.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace adrsph {

void DisplacementMonitor::reset(std::span<const double> x, std::span<const double> y) {
  const std::size_t n = x.size();
  xb_.resize(n);
  yb_.resize(n);
  double extent = 0.0;
#pragma omp parallel for schedule(static) reduction(max : extent)
  for (std::size_t i = 0; i < n; ++i) {
    xb_[i] = static_cast<float>(x[i]);
    yb_[i] = static_cast<float>(y[i]);
    extent = std::max(extent, std::max(std::fabs(x[i]), std::fabs(y[i])));
  }
  rounding_ = extent * FLT_EPSILON;  // half an ulp is eps/2 of the value; keep a factor 2
}

double DisplacementMonitor::max_relative(const CellGrid& grid, std::span<const double> x,
                                         std::span<const double> y) {
  const int nx = grid.nx(), ny = grid.ny();
  const int cells = nx * ny;
  box_.resize(4 * static_cast<std::size_t>(cells));
  float* box = box_.data();
  // Displacement bounding box of every cell's particles (contiguous after the sort).
#pragma omp parallel for schedule(static)
  for (int r = 0; r < cells; ++r) {
    float lx = FLT_MAX, hx = -FLT_MAX, ly = FLT_MAX, hy = -FLT_MAX;
    for (std::uint32_t i = grid.cell_start(r); i < grid.cell_start(r + 1); ++i) {
      const auto dx = static_cast<float>(x[i] - xb_[i]), dy = static_cast<float>(y[i] - yb_[i]);
      lx = std::min(lx, dx);
      hx = std::max(hx, dx);
      ly = std::min(ly, dy);
      hy = std::max(hy, dy);
    }
    box[4 * r] = lx;
    box[4 * r + 1] = hx;
    box[4 * r + 2] = ly;
    box[4 * r + 3] = hy;
  }
  // Spread of the union of the two boxes over each cell and its neighbours (half stencil:
  // every unordered pair of adjacent cells once, the cell with itself included).
  double worst2 = 0.0;
#pragma omp parallel for schedule(static) reduction(max : worst2)
  for (int cy = 0; cy < ny; ++cy) {
    for (int cx = 0; cx < nx; ++cx) {
      const int a = grid.rank(cx, cy);
      if (box[4 * a] > box[4 * a + 1]) continue;  // empty cell
      constexpr int stencil[5][2] = {{0, 0}, {1, 0}, {-1, 1}, {0, 1}, {1, 1}};
      for (const auto& o : stencil) {
        const int b = grid.rank(cx + o[0], cy + o[1]);
        if (b < 0 || box[4 * b] > box[4 * b + 1]) continue;
        const double sx =
            std::max(box[4 * a + 1], box[4 * b + 1]) - std::min(box[4 * a], box[4 * b]);
        const double sy =
            std::max(box[4 * a + 3], box[4 * b + 3]) - std::min(box[4 * a + 2], box[4 * b + 2]);
        worst2 = std::max(worst2, sx * sx + sy * sy);
      }
    }
  }
  // Float build positions and displacements: each d_i carries up to `rounding_` plus the
  // rounding of the displacement itself.
  return std::sqrt(worst2) + 2.0 * rounding_;
}

}  // namespace adrsph
