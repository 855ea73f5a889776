// Uniform cell grid over a fixed box, cells numbered along a Morton (Z-order) curve so that
// particles sorted by cell are close in memory when close in space. A counting sort by cell
// (no comparisons) gives the particle order and each cell's start offset.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

namespace adrsph {

class CellGrid {
 public:
  CellGrid() = default;
  // Box [xmin, xmax] x [ymin, ymax]; cells at least `cell_size` wide.
  CellGrid(double xmin, double xmax, double ymin, double ymax, double cell_size);

  int nx() const { return nx_; }
  int ny() const { return ny_; }
  bool inside(double x, double y) const {
    return x >= xmin_ && x < xmax_ && y >= ymin_ && y < ymax_;
  }
  int cell_x(double x) const { return static_cast<int>((x - xmin_) * inv_cell_); }
  int cell_y(double y) const { return static_cast<int>((y - ymin_) * inv_cell_); }
  // Morton rank of cell (cx, cy); -1 outside the grid.
  int rank(int cx, int cy) const {
    return (cx < 0 || cy < 0 || cx >= nx_ || cy >= ny_) ? -1 : rank_[cy * nx_ + cx];
  }

  // Counting sort of the particles by cell rank. `order` receives the new order (old indices)
  // of the particles that are inside the box; the ones outside are returned in `outside`.
  void sort(std::span<const double> x, std::span<const double> y, std::vector<std::uint32_t>& order,
            std::vector<std::uint32_t>& outside);

  // After sort(): particles of cell rank r are [cell_start(r), cell_start(r + 1)) in sorted order.
  std::uint32_t cell_start(int r) const { return start_[r]; }
  std::span<const std::uint32_t> starts() const { return start_; }

 private:
  double xmin_ = 0, xmax_ = 0, ymin_ = 0, ymax_ = 0, inv_cell_ = 1;
  int nx_ = 0, ny_ = 0;
  std::vector<int> rank_;             // cell id (cy * nx + cx) -> Morton rank
  std::vector<std::uint32_t> start_;  // size n_cells + 1
  std::vector<int> particle_rank_;    // scratch
};

}  // namespace adrsph
