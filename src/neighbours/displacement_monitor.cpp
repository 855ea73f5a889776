#include "neighbours/displacement_monitor.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <stdexcept>

namespace adrsph {

namespace {
constexpr double kLevels = 65535.0;

// The origin of the fixed-point range of cell rank r: half a cell below its lower-left corner.
struct Origin {
  double x, y;
};
Origin range_origin(const CellGrid& grid, int r) {
  const double half = 0.5 * grid.cell_size();
  return {grid.cell_x0(r) - half, grid.cell_y0(r) - half};
}
}  // namespace

void DisplacementMonitor::reset(const CellGrid& grid, std::span<const double> x,
                                std::span<const double> y, std::vector<std::uint32_t> storage) {
  const std::size_t n = x.size();
  const int cells = grid.cells();
  if (grid.cell_start(cells) != n)
    throw std::logic_error("DisplacementMonitor::reset: the particles are not sorted by the grid");
  packed_ = std::move(storage);
  packed_.resize(n);
  step_ = 2.0 * grid.cell_size() / kLevels;
  const double inv_step = 1.0 / step_;
  double error = 0.0;
#pragma omp parallel for schedule(static) reduction(max : error)
  for (int r = 0; r < cells; ++r) {
    const auto [ox, oy] = range_origin(grid, r);
    for (std::uint32_t i = grid.cell_start(r); i < grid.cell_start(r + 1); ++i) {
      // Clamped, so a particle outside its cell is stored wrongly but not wrapped around; the
      // error it makes is measured and enters the bound.
      const double qx = std::clamp(std::nearbyint((x[i] - ox) * inv_step), 0.0, kLevels);
      const double qy = std::clamp(std::nearbyint((y[i] - oy) * inv_step), 0.0, kLevels);
      packed_[i] = static_cast<std::uint32_t>(qx) << 16 | static_cast<std::uint32_t>(qy);
      error =
          std::max({error, std::fabs(ox + qx * step_ - x[i]), std::fabs(oy + qy * step_ - y[i])});
    }
  }
  error_ = error;
}

double DisplacementMonitor::max_relative(const CellGrid& grid, std::span<const double> x,
                                         std::span<const double> y) {
  const int nx = grid.nx(), ny = grid.ny();
  const int cells = nx * ny;
  box_.resize(4 * static_cast<std::size_t>(cells));
  float* box = box_.data();
  // Displacement bounding box of every cell's particles (contiguous after the sort).
  double largest = 0.0;  // largest |displacement component|, for the float rounding
#pragma omp parallel for schedule(static) reduction(max : largest)
  for (int r = 0; r < cells; ++r) {
    const auto [ox, oy] = range_origin(grid, r);
    float lx = FLT_MAX, hx = -FLT_MAX, ly = FLT_MAX, hy = -FLT_MAX;
    for (std::uint32_t i = grid.cell_start(r); i < grid.cell_start(r + 1); ++i) {
      const double xb = ox + static_cast<double>(packed_[i] >> 16) * step_;
      const double yb = oy + static_cast<double>(packed_[i] & 0xffffu) * step_;
      const auto dx = static_cast<float>(x[i] - xb), dy = static_cast<float>(y[i] - yb);
      lx = std::min(lx, dx);
      hx = std::max(hx, dx);
      ly = std::min(ly, dy);
      hy = std::max(hy, dy);
    }
    box[4 * r] = lx;
    box[4 * r + 1] = hx;
    box[4 * r + 2] = ly;
    box[4 * r + 3] = hy;
    if (lx <= hx)
      largest = std::max({largest, static_cast<double>(-lx), static_cast<double>(hx),
                          static_cast<double>(-ly), static_cast<double>(hy)});
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
  // Each stored build position is off by up to error_ per coordinate (sqrt(2) error_ as a
  // vector), so a pair's displacement difference by twice that; each float displacement
  // component is rounded by at most half an ulp of the largest.
  return std::sqrt(worst2) + 2.0 * std::sqrt(2.0) * error_ + 2.0 * largest * FLT_EPSILON;
}

}  // namespace adrsph
