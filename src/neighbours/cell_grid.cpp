#include "neighbours/cell_grid.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace adrsph {

namespace {
// Interleave the bits of x and y (x in the even bits): the Morton code of a cell.
std::uint64_t morton_code(std::uint32_t x, std::uint32_t y) {
  std::uint64_t code = 0;
  for (int b = 0; b < 32; ++b) {
    code |= static_cast<std::uint64_t>((x >> b) & 1u) << (2 * b);
    code |= static_cast<std::uint64_t>((y >> b) & 1u) << (2 * b + 1);
  }
  return code;
}
}  // namespace

CellGrid::CellGrid(double xmin, double xmax, double ymin, double ymax, double cell_size)
    : xmin_(xmin), ymin_(ymin), inv_cell_(1.0 / cell_size), cell_(cell_size) {
  nx_ = std::max(1, static_cast<int>(std::ceil((xmax - xmin) / cell_size)));
  ny_ = std::max(1, static_cast<int>(std::ceil((ymax - ymin) / cell_size)));
  xmax_ = xmin_ + nx_ * cell_size;
  ymax_ = ymin_ + ny_ * cell_size;
  const int n = nx_ * ny_;
  std::vector<int> ids(n);
  std::iota(ids.begin(), ids.end(), 0);
  std::sort(ids.begin(), ids.end(), [&](int a, int b) {
    return morton_code(a % nx_, a / nx_) < morton_code(b % nx_, b / nx_);
  });
  rank_.assign(n, 0);
  for (int r = 0; r < n; ++r) rank_[ids[r]] = r;
  cell_of_rank_ = std::move(ids);
  start_.assign(n + 1, 0);
}

void CellGrid::sort(std::span<const double> x, std::span<const double> y,
                    std::vector<std::uint32_t>& order, std::vector<std::uint32_t>& outside) {
  const std::size_t n = x.size();
  const int ncell = nx_ * ny_;
  // The cell rank of particle i, or -1 outside the box. Evaluated twice (count, then place)
  // rather than stored: a rank array was four bytes per particle at every re-sort.
  auto rank_of = [&](std::size_t i) {
    if (!inside(x[i], y[i]) || !std::isfinite(x[i]) || !std::isfinite(y[i])) return -1;
    return rank_[cell_y(y[i]) * nx_ + cell_x(x[i])];
  };
  outside.clear();
  std::fill(start_.begin(), start_.end(), 0u);
  for (std::size_t i = 0; i < n; ++i) {
    const int r = rank_of(i);
    if (r < 0)
      outside.push_back(static_cast<std::uint32_t>(i));
    else
      ++start_[r + 1];
  }
  for (int r = 0; r < ncell; ++r) start_[r + 1] += start_[r];
  order.resize(n - outside.size());
  std::vector<std::uint32_t> fill(start_.begin(), start_.end() - 1);
  for (std::size_t i = 0; i < n; ++i) {
    const int r = rank_of(i);
    if (r >= 0) order[fill[r]++] = static_cast<std::uint32_t>(i);
  }
}

}  // namespace adrsph
