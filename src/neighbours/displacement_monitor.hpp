// When must the cached neighbour lists be rebuilt?
//
// The lists hold every pair within `reach` = support + skin at the build. A pair missing from
// them was farther than reach apart; it can interact once it has closed in by more than the
// skin. With d the displacement since the build, and r0 a missing pair's separation at the
// build (|r0| > reach), write the relative displacement as an affine part and a rest,
//   d_i - d_j = A r0 + w,   |w| <= E.
// The pair's separation now is |(I + A) r0 + w| >= sigma |r0| - E > reach - ((1 - sigma)
// reach + E), sigma the smallest singular value of I + A: the pair closed in by less than
// (1 - sigma) reach + E. For a shear A = [[0, t], [0, 0]], 1 - sigma ~ t / 2: a pair at 45
// degrees to the flow closes in by half the shear over its separation, and no pair by more.
//
// A is fitted per cell (least squares of the displacement against the build position) and E
// bounds what the fits leave over the particles of two cells. In a channel the displacement
// is close to linear across a cell (a shear), so E stays small and the bound grows with half
// the shear over one reach, where a bound on |d_i - d_j| over two adjacent cells grows with the
// whole shear over two cells. Next to a wall the displacement has a kink (fluid sheared, walls
// at rest) that no affine field fits, and the bound there is about half the wall shear over a
// reach: that is what ends the lists now. In the fine channel run they last 7.3 steps instead
// of 4.0 (perf/README.md, 3.23).
//
// Which pairs are covered: those of the same cell or of cells up to two apart, each with the
// separation the cells' gap guarantees (and, two apart, also through the gap's component
// alone); pairs of cells farther apart are at least two cells apart in x or in y, and close in
// by at most the range of that component of d over all particles.
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
  // How far pairs that were more than `reach` apart at the build (reach <= the cell size) may
  // have closed in since: every such pair is now more than reach - max_closing() apart. Lists
  // built to reach = support + skin hold every pair within the support while
  // max_closing() <= skin. `progress` grows with the displacements since the build (the time,
  // or a bound on the distance moved): each call fits the displacement's gradient per cell,
  // and the next call scales that fit by the ratio of progress to predict its own (the bound
  // holds whatever the prediction; a good one makes it tight).
  double max_closing(const CellGrid& grid, std::span<const double> x, std::span<const double> y,
                     double reach, double progress);
  // Hand out the array of build positions (one 32-bit word per particle): a re-sort uses it
  // for its order, which is dead once the store is permuted, then gives it back to reset().
  // Until then the monitor holds nothing and max_closing() must not be called.
  std::vector<std::uint32_t> release_storage() { return std::move(packed_); }

 private:
  // Build position of each particle, relative to the lower-left corner of its cell at the
  // build, in 16-bit fixed point per coordinate (x in the high half): steps of 2 cell / 65535
  // over [-cell / 2, 3 cell / 2). Four bytes a particle instead of eight for two floats.
  std::vector<std::uint32_t> packed_;
  // Per cell, row-major with a border of two empty cells left, right and above (so that
  // every neighbour up to two cells right or up has an index). Set at a build: filled (1: the
  // cell holds particles, else 0 and every other value 0), the mean build position (mx, my)
  // from the cell centre, and the largest |X|, |Y| of X = x_build - (centre + mean) (rounded
  // up). Set by max_closing(): the gradient A its box was taken with, and the box of
  // f = d - A X (rounded outwards). One array per quantity: the pair loop reads them in
  // order, eight cells at a time.
  struct CellFits {
    // What the sweep over the particles reads and writes of a cell, together: the inverse of
    // the build positions' covariance plus a ridge, and the last call's fitted gradient (at
    // the last call's progress).
    struct State {
      float ixx = 0, ixy = 0, iyy = 0, n11 = 0, n12 = 0, n21 = 0, n22 = 0;
    };
    int stride = 0;  // cells per padded row
    std::vector<float> filled, mx, my, ex, ey;
    std::vector<float> a11, a12, a21, a22, lo_x, hi_x, lo_y, hi_y;
    std::vector<State> state;
    // The arrays from cell `at` on, for the pair loop (cell at + k is row[k]).
    struct Row {
      const float *filled, *mx, *my, *ex, *ey, *a11, *a12, *a21, *a22, *lo_x, *hi_x, *lo_y, *hi_y;
    };
    Row row(std::size_t at) const {
      return {filled.data() + at, mx.data() + at,   my.data() + at,   ex.data() + at,
              ey.data() + at,     a11.data() + at,  a12.data() + at,  a21.data() + at,
              a22.data() + at,    lo_x.data() + at, hi_x.data() + at, lo_y.data() + at,
              hi_y.data() + at};
    }
    void resize(std::size_t cells);
    std::size_t index(int cx, int cy) const {
      return static_cast<std::size_t>(cy) * static_cast<std::size_t>(stride) +
             static_cast<std::size_t>(cx + 2);
    }
  };
  // Largest closing of pairs from cell row cy to the cells (ox, oy) away; out: nx floats of
  // scratch.
  template <bool Gap>
  double row_closing(int cy, int nx, int ox, int oy, double cell, double reach, float* out) const;
  CellFits fits_;
  double step_ = 0.0;   // the fixed-point step [mm]
  double error_ = 0.0;  // largest |x_build - stored x| of any particle and coordinate
  double outside_ = 0.0;
  double progress_ = 0.0;  // of the last call since the build (0: none yet)  // largest distance of
                           // a build position from its cell (0 when sorted)
};

}  // namespace adrsph
