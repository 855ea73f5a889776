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

#include <cstdint>
#include <span>
#include <vector>

#include "neighbours/cell_grid.hpp"

namespace adrsph {

class DisplacementMonitor {
 public:
  // At a build: remember the positions. The particles must be sorted by `grid` (each in its
  // cell's range of grid.cell_start()). `storage`, if given, becomes the array the positions
  // are kept in (see release_storage()).
  void reset(const CellGrid& grid, std::span<const double> x, std::span<const double> y,
             std::vector<std::uint32_t> storage = {});
  // Upper bound of |d_i - d_j| over all pairs of particles in the same or adjacent cells.
  double max_relative(const CellGrid& grid, std::span<const double> x, std::span<const double> y);
  // Hand out the array of build positions (one 32-bit word per particle): a re-sort uses it
  // for its order, which is dead once the store is permuted, then gives it back to reset().
  // Until then the monitor holds nothing and max_relative() must not be called.
  std::vector<std::uint32_t> release_storage() { return std::move(packed_); }

 private:
  // Build position of each particle, relative to the lower-left corner of its cell at the
  // build, in 16-bit fixed point per coordinate (x in the high half): steps of 2 cell / 65535
  // over [-cell / 2, 3 cell / 2). Four bytes a particle instead of eight for two floats.
  std::vector<std::uint32_t> packed_;
  std::vector<float> box_;  // per cell rank: min dx, max dx, min dy, max dy
  double step_ = 0.0;       // the fixed-point step [mm]
  double error_ = 0.0;      // largest |x_build - stored x| of any particle and coordinate
};

}  // namespace adrsph
