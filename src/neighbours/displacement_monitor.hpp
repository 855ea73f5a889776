// When must the cached neighbour lists be rebuilt?
//
// A pair (i, j) missing from the lists was farther apart than the cut-off 3h + skin at the
// build. It can interact (come within 3h) only once |d_i - d_j| > skin, with d the displacement
// since the build. Such a pair sat in the same or in adjacent cells at the build (cells are at
// least one cut-off wide), so a bound of |d_i - d_j| over every pair of adjacent cells is a
// safe test. In a channel the particles of two adjacent cells move almost together: the bound
// grows with the shear across two cells, not with the flow speed, and the lists last several
// times longer than the usual "max |d| > skin / 2" rule allows.
#pragma once

#include <span>
#include <vector>

#include "neighbours/cell_grid.hpp"

namespace adrsph {

class DisplacementMonitor {
 public:
  // At a build: remember the positions (the particles are sorted by `grid` cell).
  void reset(std::span<const double> x, std::span<const double> y);
  // Upper bound of |d_i - d_j| over all pairs of particles in the same or adjacent cells.
  double max_relative(const CellGrid& grid, std::span<const double> x, std::span<const double> y);

 private:
  std::vector<float> xb_, yb_;  // build positions (float: the bound adds their rounding)
  std::vector<float> box_;      // per cell rank: min dx, max dx, min dy, max dy
  double rounding_ = 0.0;       // bound of |x_build - xb| over all particles
};

}  // namespace adrsph
