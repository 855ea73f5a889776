#include "neighbours/displacement_monitor.hpp"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <stdexcept>

namespace adrsph {

namespace {
constexpr double kLevels = 65535.0;
// Ridge of the gradient fit, per particle, in cell^2: a cell filled evenly spreads its
// particles' positions by cell^2 / 12 per direction, so its fitted gradient shrinks by 3%.
constexpr double kRidge = 0.0025;

// By value, so that g++ turns them into vector min / max (std::max's reference is a branch).
inline float vmax(float a, float b) {
  return a > b ? a : b;
}
inline float vmin(float a, float b) {
  return a < b ? a : b;
}

// A double as a float no larger (down) or no smaller (up): the boxes stay bounds. Widened by
// 2^-23 of the value (at least an ulp of the float) and 1e-30 before the rounding to nearest,
// which moves it by at most half an ulp: no branch and no libm call, once per cell and box.
float down(double v) {
  return static_cast<float>(v - std::fabs(v) * 0x1p-23 - 1e-30);
}
float up(double v) {
  return static_cast<float>(v + std::fabs(v) * 0x1p-23 + 1e-30);
}
}  // namespace

void DisplacementMonitor::CellFits::resize(std::size_t cells) {
  for (auto* v : {&filled, &mx, &my, &ex, &ey, &a11, &a12, &a21, &a22, &lo_x, &hi_x, &lo_y, &hi_y})
    v->resize(cells);
  state.resize(cells);
}

// How far pairs (i in cell a, j in cell b) that were more than `reach` apart at the build may
// have closed in, for every cell a of row cy and b (ox, oy) cells from it. The smaller of two
// bounds:
// - affine: with X from each cell's reference point c and f = d - A_cell X in the cell's box,
//   for any A
//     d_i - d_j = A r0 + A (c_b - c_a) + (A_a - A) X_i - (A_b - A) X_j + (f_i - f_j);
//   here A = (A_a + A_b) / 2, so the middle terms are |A_a - A_b| / 2 times the cells' extents
//   e_a + e_b, and w = d_i - d_j - A r0 is bounded componentwise. The pair is at least g
//   apart at the build (the reach, or the cells' gap if larger), and
//   |r0 + A r0 + w| >= sigma_min(I + A) g - |w| (header);
// - cells two apart (Gap): the gap between them in x or y, less the largest closing of that
//   component of d_i - d_j (a wall cell and a sheared fluid cell two rows up close in by the
//   tiny y motion only, though their x displacements differ by the shear over three rows).
// Written over one row so that the cells' arrays are read in order: the loop is vectorised.
// In float, eight cells a vector: the closing is a sum of terms (the reach, sigma g, and |w|
// from the boxes, K and the extents) each rounded fewer than 30 times at 6e-8; kFloatSlack
// times the sum of their magnitudes covers the rounding.
template <bool Gap>
double DisplacementMonitor::row_closing(int cy, int nx, int ox, int oy, double cell, double reach,
                                        float* out) const {
  constexpr float kFloatSlack = 4e-6f;
  const CellFits& f = fits_;
  const double gap_xd = std::max(std::abs(ox) - 1, 0) * cell;
  const double gap_yd = std::max(oy - 1, 0) * cell;
  const auto gap_x = static_cast<float>(gap_xd), gap_y = static_cast<float>(gap_yd);
  const auto g = static_cast<float>(std::max(reach, std::sqrt(gap_xd * gap_xd + gap_yd * gap_yd)));
  const auto r = static_cast<float>(reach);
  const auto ocx = static_cast<float>(ox * cell), ocy = static_cast<float>(oy * cell);
  // Cell a = first + k of the row, b = a + shift.
  const std::size_t first = f.index(0, cy);
  const std::size_t shifted = f.index(ox, cy + oy);
  const CellFits::Row a = f.row(first), b = f.row(shifted);
  // b right of a (ox > 0): r0_x <= -gap_x, and d_i,x - d_j,x <= hi_a - lo_b closes it; b left
  // of a: hi_b - lo_a. As s * (hi_a - lo_b) + (1 - s) * (hi_b - lo_a) without a branch.
  const float right = ox > 0 ? 1.0f : 0.0f;
#pragma omp simd
  for (int k = 0; k < nx; ++k) {
    const float a11 = 0.5f * (a.a11[k] + b.a11[k]), a12 = 0.5f * (a.a12[k] + b.a12[k]);
    const float a21 = 0.5f * (a.a21[k] + b.a21[k]), a22 = 0.5f * (a.a22[k] + b.a22[k]);
    const float d11 = 0.5f * std::fabs(a.a11[k] - b.a11[k]),
                d12 = 0.5f * std::fabs(a.a12[k] - b.a12[k]);
    const float d21 = 0.5f * std::fabs(a.a21[k] - b.a21[k]),
                d22 = 0.5f * std::fabs(a.a22[k] - b.a22[k]);
    const float ex = a.ex[k] + b.ex[k], ey = a.ey[k] + b.ey[k];
    // c_b - c_a: the cells' offset and their mean build positions.
    const float cbx = ocx + (b.mx[k] - a.mx[k]), cby = ocy + (b.my[k] - a.my[k]);
    const float kx = a11 * cbx + a12 * cby, ky = a21 * cbx + a22 * cby;
    const float wx =
        vmax(std::fabs(kx + a.lo_x[k] - b.hi_x[k]), std::fabs(kx + a.hi_x[k] - b.lo_x[k])) +
        d11 * ex + d12 * ey;
    const float wy =
        vmax(std::fabs(ky + a.lo_y[k] - b.hi_y[k]), std::fabs(ky + a.hi_y[k] - b.lo_y[k])) +
        d21 * ex + d22 * ey;
    // Smallest singular value of M = I + A, [[p, q], [r, s]]:
    // (sqrt((p + s)^2 + (q - r)^2) - sqrt((p - s)^2 + (q + r)^2)) / 2, without cancellation
    // near A = 0. For a shear A = [[0, t], [0, 0]] it is ~ 1 - t / 2: a pair at 45 degrees
    // closes in by half its shear; 1 - ||A|| would count the whole shear.
    const float ps = 2.0f + a11 + a22, qr = a12 - a21, pms = a11 - a22, qpr = a12 + a21;
    const float sigma =
        vmax(0.0f, 0.5f * (std::sqrt(ps * ps + qr * qr) - std::sqrt(pms * pms + qpr * qpr)));
    const float w = std::sqrt(wx * wx + wy * wy);
    float closing = w + r - sigma * g;
    float size = r + g + std::fabs(kx) + std::fabs(ky) + std::fabs(a.lo_x[k]) +
                 std::fabs(a.hi_x[k]) + std::fabs(a.lo_y[k]) + std::fabs(a.hi_y[k]) +
                 std::fabs(b.lo_x[k]) + std::fabs(b.hi_x[k]) + std::fabs(b.lo_y[k]) +
                 std::fabs(b.hi_y[k]) + (d11 + d12 + d21 + d22) * (ex + ey);
    if constexpr (Gap) {
      // The displacement boxes d = f + A_cell X, with |X| <= e per component.
      const float sxa = std::fabs(a.a11[k]) * a.ex[k] + std::fabs(a.a12[k]) * a.ey[k];
      const float sya = std::fabs(a.a21[k]) * a.ex[k] + std::fabs(a.a22[k]) * a.ey[k];
      const float sxb = std::fabs(b.a11[k]) * b.ex[k] + std::fabs(b.a12[k]) * b.ey[k];
      const float syb = std::fabs(b.a21[k]) * b.ex[k] + std::fabs(b.a22[k]) * b.ey[k];
      const float close_x = right * ((a.hi_x[k] + sxa) - (b.lo_x[k] - sxb)) +
                            (1.0f - right) * ((b.hi_x[k] + sxb) - (a.lo_x[k] - sxa));
      const float close_y = (a.hi_y[k] + sya) - (b.lo_y[k] - syb);  // b above a (oy >= 0)
      // A zero gap adds nothing: max(0 - close, 0) * 0.
      const float sep_x = vmax(gap_x - close_x, 0.0f) * (gap_x > 0.0f ? 1.0f : 0.0f);
      const float sep_y = vmax(gap_y - close_y, 0.0f) * (gap_y > 0.0f ? 1.0f : 0.0f);
      closing = vmin(closing, r - std::sqrt(sep_x * sep_x + sep_y * sep_y));
      size += gap_x + gap_y + sxa + sya + sxb + syb;
    }
    closing += kFloatSlack * size;
    out[k] = closing * a.filled[k] * b.filled[k];  // 0 unless both cells hold particles
  }
  float worst = 0.0f;
  for (int k = 0; k < nx; ++k) worst = vmax(worst, out[k]);
  return worst;
}

// Visit the cells of row cy in order: visit(cx, r, x0, y0) with r the cell's rank and (x0, y0)
// its lower-left corner.
template <class Visit>
void for_each_cell_row(const CellGrid& grid, int cy, Visit&& visit) {
  const int r00 = grid.rank(0, 0);
  const double x00 = grid.cell_x0(r00), y00 = grid.cell_y0(r00), cell = grid.cell_size();
  for (int cx = 0; cx < grid.nx(); ++cx)
    visit(cx, grid.rank(cx, cy), x00 + cx * cell, y00 + cy * cell);
}

void DisplacementMonitor::reset(const CellGrid& grid, std::span<const double> x,
                                std::span<const double> y, std::vector<std::uint32_t> storage) {
  const std::size_t n = x.size();
  const int nx = grid.nx(), ny = grid.ny();
  if (grid.cell_start(nx * ny) != n)
    throw std::logic_error("DisplacementMonitor::reset: the particles are not sorted by the grid");
  packed_ = std::move(storage);
  packed_.resize(n);
  const double cell = grid.cell_size();
  step_ = 2.0 * cell / kLevels;
  const double inv_step = 1.0 / step_;
  CellFits& fits = fits_;
  fits.stride = nx + 4;
  fits.resize(static_cast<std::size_t>(fits.stride) * static_cast<std::size_t>(ny + 2));
  // The border and the empty cells stay empty (filled 0) with every bound 0.
  for (auto* v : {&fits.a11, &fits.a12, &fits.a21, &fits.a22, &fits.lo_x, &fits.hi_x, &fits.lo_y,
                  &fits.hi_y, &fits.ex, &fits.ey, &fits.mx, &fits.my, &fits.filled})
    std::fill(v->begin(), v->end(), 0.0f);
  std::fill(fits.state.begin(), fits.state.end(), CellFits::State{});
  double error = 0.0, outside = 0.0;
#pragma omp parallel for schedule(static) reduction(max : error, outside)
  for (int cy = 0; cy < ny; ++cy) {
    for_each_cell_row(grid, cy, [&](int cx, int r, double x0, double y0) {
      const double ox = x0 - 0.5 * cell, oy = y0 - 0.5 * cell;  // the fixed point's origin
      const double centre_x = x0 + 0.5 * cell, centre_y = y0 + 0.5 * cell;  // the cell centre
      const std::uint32_t first = grid.cell_start(r), last = grid.cell_start(r + 1);
      if (first == last) return;
      double sX = 0, sY = 0, sXX = 0, sXY = 0, sYY = 0;
      double lx = DBL_MAX, hx = -DBL_MAX, ly = DBL_MAX, hy = -DBL_MAX;
      for (std::uint32_t i = first; i < last; ++i) {
        // Clamped, so a particle outside its cell is stored wrongly but not wrapped around;
        // the error it makes is measured and enters the bound.
        const double qx = std::clamp(std::nearbyint((x[i] - ox) * inv_step), 0.0, kLevels);
        const double qy = std::clamp(std::nearbyint((y[i] - oy) * inv_step), 0.0, kLevels);
        packed_[i] = static_cast<std::uint32_t>(qx) << 16 | static_cast<std::uint32_t>(qy);
        const double xb = ox + qx * step_, yb = oy + qy * step_;
        error = std::max({error, std::fabs(xb - x[i]), std::fabs(yb - y[i])});
        outside = std::max({outside, x0 - x[i], x[i] - (x0 + cell), y0 - y[i], y[i] - (y0 + cell)});
        const double X = xb - centre_x, Y = yb - centre_y;
        sX += X, sY += Y, sXX += X * X, sXY += X * Y, sYY += Y * Y;
        lx = std::min(lx, X), hx = std::max(hx, X), ly = std::min(ly, Y), hy = std::max(hy, Y);
      }
      // The build positions' moments, for the gradient fits: mean, and the inverse of the
      // covariance plus a ridge. The ridge keeps a cell whose particles spread little in a
      // direction (a strip at a wall, a cell just filling) from fitting its noise into a steep
      // gradient.
      const double m = 1.0 / static_cast<double>(last - first);
      const double mx = sX * m, my = sY * m, ridge = kRidge * cell * cell;
      const double cxx = sXX * m - mx * mx + ridge, cxy = sXY * m - mx * my,
                   cyy = sYY * m - my * my + ridge;
      const double det = cxx * cyy - cxy * cxy;  // >= ridge^2 > 0
      const std::size_t k = fits.index(cx, cy);
      fits.filled[k] = 1.0f;
      // The cell's reference point: its mean build position (as stored), so that a cell
      // filled in a strip has small extents about it.
      const auto mxf = static_cast<float>(mx), myf = static_cast<float>(my);
      fits.mx[k] = mxf, fits.my[k] = myf;
      fits.state[k] = {static_cast<float>(cyy / det),
                       static_cast<float>(-cxy / det),
                       static_cast<float>(cxx / det),
                       0.0f,
                       0.0f,
                       0.0f,
                       0.0f};
      fits.ex[k] = up(std::max(hx - mxf, mxf - lx)), fits.ey[k] = up(std::max(hy - myf, myf - ly));
    });
  }
  error_ = error;
  outside_ = outside;
  progress_ = 0.0;
}

double DisplacementMonitor::max_closing(const CellGrid& grid, std::span<const double> x,
                                        std::span<const double> y, double reach, double progress) {
  const double cell = grid.cell_size();
  if (!(reach > 0.0 && reach <= cell))
    throw std::logic_error("DisplacementMonitor::max_closing: reach must be in (0, cell size]");
  const int nx = grid.nx(), ny = grid.ny();
  CellFits& fits = fits_;
  const double grow = progress_ > 0.0 ? progress / progress_ : 0.0;
  progress_ = progress;

  // Per cell, in one sweep over its particles (contiguous after the sort): the box of what a
  // gradient A leaves of the displacement, f = d - A X, and the least-squares gradient. Any A
  // gives a valid bound (the box is of d - A X with the A stored); a good one makes the box
  // small.
  // The range of each component of d over all particles, for the pairs of cells farther apart.
  double low_u = DBL_MAX, high_u = -DBL_MAX, low_v = DBL_MAX, high_v = -DBL_MAX;
  double scale = 0.0;  // largest |coordinate|, for the rounding of the displacements
#pragma omp parallel for schedule(static) reduction(min             \
                                                    : low_u, low_v) \
    reduction(max                                                   \
              : high_u, high_v, scale)
  for (int cy = 0; cy < ny; ++cy) {
    for_each_cell_row(grid, cy, [&](int cx, int r, double x0, double y0) {
      const std::uint32_t first = grid.cell_start(r), last = grid.cell_start(r + 1);
      if (first == last) return;
      const double ox = x0 - 0.5 * cell, oy = y0 - 0.5 * cell;
      const std::size_t k = fits.index(cx, cy);
      // The reference point: the cell centre plus the cell's mean build position.
      const double centre_x = x0 + 0.5 * cell, centre_y = y0 + 0.5 * cell, mx = fits.mx[k],
                   my = fits.my[k];
      scale = std::max({scale, std::fabs(ox), std::fabs(oy), std::fabs(ox + 2 * cell),
                        std::fabs(oy + 2 * cell)});
      // The gradient the box is taken with: the last call's fit, scaled to this call's
      // progress (exact while the displacements grow in proportion).
      CellFits::State& state = fits.state[k];
      const auto a11 = static_cast<float>(grow * state.n11);
      const auto a12 = static_cast<float>(grow * state.n12);
      const auto a21 = static_cast<float>(grow * state.n21);
      const auto a22 = static_cast<float>(grow * state.n22);
      // Per particle: build position X (from the reference point), displacement (u, v).
      const std::uint32_t* packed = packed_.data() + first;
      const double* px = x.data() + first;
      const double* py = y.data() + first;
      const double step = step_, rx = centre_x + mx - ox, ry = centre_y + my - oy;
      const int count = static_cast<int>(last - first);
      double su = 0, sv = 0, sXu = 0, sYu = 0, sXv = 0, sYv = 0;
      double lx = DBL_MAX, hx = -DBL_MAX, ly = DBL_MAX, hy = -DBL_MAX;
#pragma omp simd reduction(+ : su, sv, sXu, sYu, sXv, sYv) reduction(min : lx, ly) \
    reduction(max : hx, hy)
      for (int i = 0; i < count; ++i) {
        const double qx = static_cast<double>(static_cast<int>(packed[i] >> 16)) * step;
        const double qy = static_cast<double>(static_cast<int>(packed[i] & 0xffffu)) * step;
        const double u = px[i] - (ox + qx), v = py[i] - (oy + qy);
        const double X = qx - rx, Y = qy - ry;
        su += u, sv += v, sXu += X * u, sYu += Y * u, sXv += X * v, sYv += Y * v;
        const double fx = u - (a11 * X + a12 * Y), fy = v - (a21 * X + a22 * Y);
        lx = lx < fx ? lx : fx, hx = hx > fx ? hx : fx, ly = ly < fy ? ly : fy,
        hy = hy > fy ? hy : fy;
      }
      // d = f + A X with |X| <= e per component.
      const double sx = std::fabs(a11) * fits.ex[k] + std::fabs(a12) * fits.ey[k];
      const double sy = std::fabs(a21) * fits.ex[k] + std::fabs(a22) * fits.ey[k];
      low_u = std::min(low_u, lx - sx), high_u = std::max(high_u, hx + sx);
      low_v = std::min(low_v, ly - sy), high_v = std::max(high_v, hy + sy);
      // This call's least-squares fit, for the next call.
      const double m = 1.0 / static_cast<double>(last - first);
      // (X is from the mean build position, as stored in float: its mean is ~0, and any
      // gradient is valid.)
      const double cxu = sXu * m, cyu = sYu * m, cxv = sXv * m, cyv = sYv * m;
      const double ixx = state.ixx, ixy = state.ixy, iyy = state.iyy;
      state.n11 = static_cast<float>(cxu * ixx + cyu * ixy);
      state.n12 = static_cast<float>(cxu * ixy + cyu * iyy);
      state.n21 = static_cast<float>(cxv * ixx + cyv * ixy);
      state.n22 = static_cast<float>(cxv * ixy + cyv * iyy);
      fits.a11[k] = a11, fits.a12[k] = a12, fits.a21[k] = a21, fits.a22[k] = a22;
      fits.lo_x[k] = down(lx), fits.hi_x[k] = up(hx), fits.lo_y[k] = down(ly),
      fits.hi_y[k] = up(hy);
    });
  }

  // Every unordered pair of cells up to two apart once (the cell with itself included).
  double worst = 0.0;
#pragma omp parallel reduction(max : worst)
  {
    std::vector<float> out(static_cast<std::size_t>(nx));  // one row's closings
#pragma omp for schedule(static)
    for (int cy = 0; cy < ny; ++cy) {
      for (int oy = 0; oy <= 2; ++oy) {
        for (int ox = -2; ox <= 2; ++ox) {
          if (oy == 0 && ox < 0) continue;  // the other cell of that pair visits it
          const bool gap = std::abs(ox) == 2 || oy == 2;
          worst =
              std::max(worst, gap ? row_closing<true>(cy, nx, ox, oy, cell, reach, out.data())
                                  : row_closing<false>(cy, nx, ox, oy, cell, reach, out.data()));
        }
      }
    }
  }
  // Pairs of cells farther apart: at least 2 cells apart at the build in x or in y, and that
  // component of d_i - d_j is within the range of d's component over all particles.
  if (low_u <= high_u)  // (no particles: no pairs)
    worst = std::max(worst, std::max(high_u - low_u, high_v - low_v) - (2.0 * cell - reach));
  // The stored build positions are off by up to error_ per coordinate and the cells' gaps
  // hold up to outside_ per coordinate (sqrt(2) times that as vectors, twice for a pair);
  // the displacements are differences of coordinates of size `scale`, rounded in double.
  return worst + 2.0 * std::sqrt(2.0) * (error_ + outside_) + 1e3 * DBL_EPSILON * (scale + cell);
}

}  // namespace adrsph
