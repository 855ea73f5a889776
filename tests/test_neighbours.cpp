// Neighbour structures: the cached lists hold exactly the pairs within the cut-off, and the
// displacement monitor never lets a pair within the kernel support go missing.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <stdexcept>
#include <utility>
#include <vector>

#include "neighbours/cell_grid.hpp"
#include "neighbours/displacement_monitor.hpp"
#include "neighbours/neighbour_list.hpp"

namespace adrsph {
namespace {

constexpr double kDx = 0.25, kSupport = 3.0 * kDx, kSkin = 0.1 * kSupport;
constexpr double kCutoff = kSupport + kSkin;

// A jittered lattice on [0, 20] x [-2.5, 2.5], sorted by cell like the solver does.
struct Cloud {
  std::vector<double> x, y;
  CellGrid grid;
  NeighbourList list;

  explicit Cloud(unsigned seed) : grid(-1.0, 25.0, -3.5, 3.5, kCutoff) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> jitter(-0.2 * kDx, 0.2 * kDx);
    std::vector<double> x0, y0;
    for (double px = 0.5 * kDx; px < 20.0; px += kDx)
      for (double py = -2.5 + 0.5 * kDx; py < 2.5; py += kDx) {
        x0.push_back(px + jitter(rng));
        y0.push_back(py + jitter(rng));
      }
    std::vector<std::uint32_t> order, outside;
    grid.sort(x0, y0, order, outside);
    EXPECT_TRUE(outside.empty());
    for (std::uint32_t k : order) {
      x.push_back(x0[k]);
      y.push_back(y0[k]);
    }
    build();
  }
  void build() {
    std::vector<std::uint32_t> order, outside;
    grid.sort(x, y, order, outside);  // (re-sort in place: order is the identity when sorted)
    EXPECT_TRUE(outside.empty());     // (the tests' fields keep every particle in the grid)
    std::vector<double> xs, ys;
    for (std::uint32_t k : order) {
      xs.push_back(x[k]);
      ys.push_back(y[k]);
    }
    x = xs;
    y = ys;
    list.build(grid, x, y, kCutoff, static_cast<std::uint32_t>(x.size()));
  }
  std::set<std::pair<std::uint32_t, std::uint32_t>> listed() const {
    std::set<std::pair<std::uint32_t, std::uint32_t>> s;
    list.with_indices([&](auto form) {
      std::vector<std::uint32_t> buffer(NeighbourList::kRowBuffer);
      for (std::size_t i = 0; i < x.size(); ++i) {
        const std::uint32_t kb = list.begin(i), ke = list.end(i);
        const std::uint32_t* row = form.row(i, kb, ke, buffer.data());
        // The real entries, then the padding particle up to a whole number of vectors.
        const std::uint32_t whole = NeighbourList::padded(ke - kb);
        EXPECT_EQ(whole % NeighbourList::kPad, 0u);
        EXPECT_LT(whole - (ke - kb), NeighbourList::kPad);
        for (std::uint32_t k = 0; k < whole; ++k) {
          if (k < ke - kb) {
            EXPECT_NE(row[k], x.size());
            s.insert({static_cast<std::uint32_t>(i), row[k]});
          } else {
            EXPECT_EQ(row[k], x.size()) << "padding of row " << i << ", entry " << k;
          }
        }
      }
    });
    return s;
  }
  double distance(std::size_t i, std::size_t j) const {
    return std::hypot(x[i] - x[j], y[i] - y[j]);
  }
};

TEST(NeighbourList, HoldsExactlyThePairsWithinTheCutoffExpandedToWholeVectors) {
  Cloud cloud(7);
  const auto listed = cloud.listed();
  const std::size_t n = cloud.x.size();
  std::size_t within = 0;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = 0; j < n; ++j) {
      if (i == j) continue;
      const bool inside = cloud.distance(i, j) < kCutoff;
      within += inside;
      EXPECT_EQ(inside,
                listed.count({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j)}) == 1)
          << "pair " << i << ", " << j << " at distance " << cloud.distance(i, j);
    }
  }
  EXPECT_EQ(within, listed.size());
  // About pi (3.3)^2 = 34 neighbours per interior particle on this lattice.
  EXPECT_NEAR(cloud.list.mean_neighbours(), 31.0, 3.0);
}

// Entry k of particle i, whatever the form of the list.
std::vector<std::uint32_t> entries(const NeighbourList& list, std::size_t n) {
  std::vector<std::uint32_t> e;
  list.with_indices([&](auto form) {
    std::vector<std::uint32_t> buffer(NeighbourList::kRowBuffer);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint32_t kb = list.begin(i), ke = list.end(i);
      const std::uint32_t* row = form.row(i, kb, ke, buffer.data());
      e.insert(e.end(), row, row + NeighbourList::padded(ke - kb));
    }
  });
  return e;
}

TEST(NeighbourList, SixteenBitOffsetsListWhatThirtyTwoBitIndicesList) {
  Cloud cloud(13);
  const std::size_t n = cloud.x.size();
  ASSERT_FALSE(cloud.list.wide());  // a channel: every offset fits 16 bits
  const auto narrow = entries(cloud.list, n);
  const std::size_t narrow_bytes = cloud.list.bytes();
  NeighbourList wide;
  wide.build(cloud.grid, cloud.x, cloud.y, kCutoff, static_cast<std::uint32_t>(n),
             NeighbourList::Width::wide);
  ASSERT_TRUE(wide.wide());
  EXPECT_EQ(entries(wide, n), narrow);  // entry by entry, the padding included
  // 2 bytes a stored entry instead of 4 (the row starts, 4 bytes a particle, alike); the 16-bit
  // form stores no padding, the 32-bit form its rows padded to whole vectors. A first build of
  // the 16-bit form keeps 1/8 of its entries spare, for the next builds to fill in one pass.
  const double starts = 4.0 * static_cast<double>(n + 1);
  EXPECT_NEAR((static_cast<double>(narrow_bytes) - starts) / cloud.list.total(), 2.0 * 9 / 8, 0.1);
  EXPECT_NEAR((static_cast<double>(wide.bytes()) - starts) / wide.total(), 4.0, 0.4);
  EXPECT_EQ(static_cast<double>(wide.total()), static_cast<double>(narrow.size()));
  EXPECT_LT(cloud.list.total(), narrow.size());
}

// Particles marked as one class (the solver's walls: here the rows within 0.5 of the cloud's
// top and bottom) list no marked particle in their rows, or nothing (whole_row); every other
// row is complete. The first (two-pass) build, a second (one-pass) build with 1 and 2 threads,
// and the 32-bit form hold exactly those pairs.
TEST(NeighbourList, RowsOfAMarkedClassLeaveOutTheirClass) {
  const int threads_before = omp_get_max_threads();
  for (const bool whole_row : {false, true})
    for (int threads : {1, 2}) {
      omp_set_num_threads(threads);
      Cloud cloud(17);
      const std::size_t n = cloud.x.size();
      constexpr std::uint8_t kMarked = 3;
      std::vector<std::uint8_t> kind(n + 1, kMarked);  // (the padding particle: marked too)
      std::size_t marked = 0;
      for (std::size_t i = 0; i < n; ++i) {
        kind[i] = std::fabs(cloud.y[i]) > 2.0 ? kMarked : 0;
        marked += kind[i] == kMarked;
      }
      ASSERT_GT(marked, n / 10);
      const NeighbourList::Omit omit{kind.data(), kMarked, whole_row};
      const auto padding = static_cast<std::uint32_t>(n);
      auto expect_rule = [&](const NeighbourList& list, const char* what) {
        std::size_t wrong = 0, expected = 0, left_out = 0;
        list.with_indices([&](auto form) {
          std::vector<std::uint32_t> buffer(NeighbourList::kRowBuffer);
          for (std::size_t i = 0; i < n; ++i) {
            const std::uint32_t kb = list.begin(i), ke = list.end(i);
            const std::uint32_t* row = form.row(i, kb, ke, buffer.data());
            std::set<std::uint32_t> got;
            for (std::uint32_t k = 0; k < NeighbourList::padded(ke - kb); ++k)
              if (row[k] != padding) got.insert(row[k]);
            std::set<std::uint32_t> want;
            for (std::size_t j = 0; j < n; ++j) {
              if (j == i || cloud.distance(i, j) >= kCutoff) continue;
              if (kind[i] == kMarked && (whole_row || kind[j] == kMarked)) {
                ++left_out;
                continue;
              }
              want.insert(static_cast<std::uint32_t>(j));
            }
            expected += want.size();
            wrong += got != want;
          }
        });
        EXPECT_EQ(wrong, 0u) << what << ", " << threads << " threads";
        EXPECT_GT(left_out, 10 * marked) << what;  // whole parts of the marked rows left out
        EXPECT_NEAR(list.mean_neighbours(), static_cast<double>(expected) / n, 1e-12) << what;
      };
      NeighbourList list, wide;
      list.build(cloud.grid, cloud.x, cloud.y, kCutoff, padding, NeighbourList::Width::automatic,
                 omit);
      EXPECT_FALSE(list.one_pass());
      expect_rule(list, "first build");
      list.build(cloud.grid, cloud.x, cloud.y, kCutoff, padding, NeighbourList::Width::automatic,
                 omit);
      EXPECT_TRUE(list.one_pass());
      expect_rule(list, "one-pass build");
      wide.build(cloud.grid, cloud.x, cloud.y, kCutoff, padding, NeighbourList::Width::wide, omit);
      expect_rule(wide, "32-bit form");
    }
  omp_set_num_threads(threads_before);
}

// The lists of `list` and of a two-pass build on the same positions, row by row.
void expect_same_as_two_pass(const Cloud& cloud, const char* what) {
  const std::size_t n = cloud.x.size();
  NeighbourList fresh;  // a first build: two passes
  fresh.build(cloud.grid, cloud.x, cloud.y, kCutoff, static_cast<std::uint32_t>(n));
  ASSERT_FALSE(fresh.one_pass());
  ASSERT_EQ(cloud.list.total(), fresh.total()) << what;
  for (std::size_t i = 0; i <= n; ++i)
    ASSERT_EQ(cloud.list.begin(i), fresh.begin(i)) << what << ": row " << i;
  EXPECT_EQ(entries(cloud.list, n), entries(fresh, n)) << what;
  EXPECT_EQ(cloud.list.mean_neighbours(), fresh.mean_neighbours()) << what;
}

// A build after the first takes one pass over the candidates, each thread storing its rows in
// a region sized from the previous build's rows; the regions are then moved together. With 1,
// 2 and 3 threads (regions to close up between shares), it lists what a two-pass build lists.
TEST(NeighbourList, OnePassBuildListsWhatTheTwoPassBuildLists) {
  const int threads_before = omp_get_max_threads();
  for (int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    Cloud cloud(29);  // built once: two passes
    EXPECT_FALSE(cloud.list.one_pass());
    std::mt19937 rng(31);
    std::uniform_real_distribution<double> move(-0.1 * kDx, 0.1 * kDx);
    for (int rebuild = 0; rebuild < 3; ++rebuild) {
      for (std::size_t i = 0; i < cloud.x.size(); ++i)
        cloud.x[i] += move(rng), cloud.y[i] += move(rng);
      cloud.build();
      EXPECT_TRUE(cloud.list.one_pass()) << threads << " threads, rebuild " << rebuild;
      expect_same_as_two_pass(cloud, "after a small motion");
    }
  }
  omp_set_num_threads(threads_before);
}

// A run from the lattice lists ~9% more pairs a few steps later, once the lattice has
// disordered: the first build leaves room for that (here the cloud is squeezed to 93% of its
// length, ~7% more neighbours), and the second build takes one pass.
TEST(NeighbourList, SecondBuildTakesOnePassWhenTheRowsGrowAsALatticeDisorders) {
  const int threads_before = omp_get_max_threads();
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    Cloud cloud(41);
    ASSERT_FALSE(cloud.list.one_pass());
    const double before = cloud.list.mean_neighbours();
    for (double& x : cloud.x) x *= 0.93;
    cloud.build();
    EXPECT_GT(cloud.list.mean_neighbours(), 1.05 * before);
    EXPECT_TRUE(cloud.list.one_pass()) << threads << " threads";
    expect_same_as_two_pass(cloud, "after the growth");
  }
  omp_set_num_threads(threads_before);
}

// When the rows grow past the headroom of their region (here the cloud is squeezed to 80% of
// its length: 25% more neighbours), the build falls back to two passes, and still lists exactly
// what it should; the build after it takes one pass again.
TEST(NeighbourList, OnePassBuildFallsBackWhenTheRowsOutgrowTheirRegion) {
  const int threads_before = omp_get_max_threads();
  for (int threads : {1, 2}) {
    omp_set_num_threads(threads);
    Cloud cloud(37);
    cloud.build();
    ASSERT_TRUE(cloud.list.one_pass());
    const double before = cloud.list.mean_neighbours();
    for (double& x : cloud.x) x *= 0.8;
    cloud.build();
    EXPECT_FALSE(cloud.list.one_pass()) << threads << " threads";
    EXPECT_GT(cloud.list.mean_neighbours(), 1.15 * before);
    expect_same_as_two_pass(cloud, "after the squeeze");
    cloud.build();
    EXPECT_TRUE(cloud.list.one_pass()) << threads << " threads";
    expect_same_as_two_pass(cloud, "the build after the squeeze");
  }
  omp_set_num_threads(threads_before);
}

// A square of 360 x 360 particles: the Morton order puts some neighbours more than 32,767
// places apart (across the middle of the square), so the list takes 32-bit indices, and still
// holds exactly the pairs within the cut-off.
TEST(NeighbourList, FallsBackToIndicesWhereAnOffsetDoesNotFitSixteenBits) {
  const int side = 360;
  const double extent = side * kDx;
  CellGrid grid(-1.0, extent + 1.0, -1.0, extent + 1.0, kCutoff);
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> jitter(-0.2 * kDx, 0.2 * kDx);
  std::vector<double> x0, y0;
  for (int a = 0; a < side; ++a)
    for (int b = 0; b < side; ++b) {
      x0.push_back((a + 0.5) * kDx + jitter(rng));
      y0.push_back((b + 0.5) * kDx + jitter(rng));
    }
  std::vector<std::uint32_t> order, outside;
  grid.sort(x0, y0, order, outside);
  ASSERT_TRUE(outside.empty());
  std::vector<double> x, y;
  for (std::uint32_t k : order) x.push_back(x0[k]), y.push_back(y0[k]);
  const std::size_t n = x.size();
  NeighbourList list;
  list.build(grid, x, y, kCutoff, static_cast<std::uint32_t>(n));
  ASSERT_TRUE(list.wide());
  std::size_t farthest = 0;
  std::vector<std::uint32_t> buffer(NeighbourList::kRowBuffer);
  for (std::size_t i = 0; i < n; i += 97) {  // every 97th particle against all the others
    std::set<std::uint32_t> listed;
    list.with_indices([&](auto form) {
      const std::uint32_t kb = list.begin(i), ke = list.end(i);
      const std::uint32_t* row = form.row(i, kb, ke, buffer.data());
      for (std::uint32_t k = 0; k < NeighbourList::padded(ke - kb); ++k)
        if (row[k] != n) listed.insert(row[k]);
    });
    std::set<std::uint32_t> within;
    for (std::size_t j = 0; j < n; ++j)
      if (j != i &&
          (x[i] - x[j]) * (x[i] - x[j]) + (y[i] - y[j]) * (y[i] - y[j]) < kCutoff * kCutoff) {
        within.insert(static_cast<std::uint32_t>(j));
        farthest = std::max(farthest, j > i ? j - i : i - j);
      }
    ASSERT_EQ(listed, within) << "particle " << i;
  }
  EXPECT_GT(farthest, static_cast<std::size_t>(NeighbourList::kMaxOffset));  // the case tested
}

// By brute force: how far the pairs that were more than `reach` apart at the build (x0, y0)
// have closed in by now (x, y): the largest reach - |r| over them (what max_closing bounds).
double true_max_closing(const std::vector<double>& x0, const std::vector<double>& y0,
                        const std::vector<double>& x, const std::vector<double>& y, double reach) {
  double worst = -reach;
  for (std::size_t i = 0; i < x.size(); ++i)
    for (std::size_t j = i + 1; j < x.size(); ++j) {
      if (std::hypot(x0[i] - x0[j], y0[i] - y0[j]) <= reach) continue;
      worst = std::max(worst, reach - std::hypot(x[i] - x[j], y[i] - y[j]));
    }
  return worst;
}

TEST(DisplacementMonitor, UniformTranslationDoesNotAgeTheLists) {
  Cloud cloud(3);
  DisplacementMonitor monitor;
  monitor.reset(cloud.grid, cloud.x, cloud.y);
  for (int call = 1; call <= 3; ++call) {  // the later calls take the gradient from the last
    for (std::size_t i = 0; i < cloud.x.size(); ++i) {
      cloud.x[i] += 5.0 * kSkin;  // far more than the skin, but all together
      cloud.y[i] -= 2.0 * kSkin;
    }
    // What is left is the 16-bit fixed point of the stored build positions (a step of
    // 2 cut-offs / 65535 = 2.5e-5 mm here), as noise in the gradients the cells fit.
    const double bound = monitor.max_closing(cloud.grid, cloud.x, cloud.y, kCutoff, call);
    EXPECT_LT(bound, 5e-3 * kSkin) << "call " << call;
  }
}

// A simple shear d = (rate y, 0): a pair at the reach closes in by at most rate reach / 2
// (at 45 degrees). The bound covers the true closing, found by brute force, and stays within
// half of 2 rate cut-off, a bound on |d_i - d_j| over two adjacent cells, even at the cloud's
// ragged edges (cells filled in strips).
TEST(DisplacementMonitor, ShearClosesPairsInByAboutHalfItsJumpOverTheReach) {
  Cloud cloud(5);
  const std::vector<double> x0 = cloud.x, y0 = cloud.y;
  DisplacementMonitor monitor;
  monitor.reset(cloud.grid, cloud.x, cloud.y);
  const double rate = 0.01;  // per call
  for (int call = 1; call <= 3; ++call) {
    for (std::size_t i = 0; i < cloud.x.size(); ++i) cloud.x[i] = x0[i] + call * rate * y0[i];
    const double bound = monitor.max_closing(cloud.grid, cloud.x, cloud.y, kCutoff, call);
    const double truth = true_max_closing(x0, y0, cloud.x, cloud.y, kCutoff);
    EXPECT_GE(bound, truth) << "call " << call;
    EXPECT_GT(truth, 0.4 * call * rate * kCutoff);  // the case tested: pairs do close in
    // The first call has no gradient to go by (the box of d itself: the shear over two rows).
    if (call > 1) {
      EXPECT_LT(bound, call * rate * kCutoff) << "call " << call;
    }
  }
}

// Walls do not move and the fluid next to them shears (d = rate (y - y_wall) above the wall,
// 0 below): no affine field, the displacement has a kink. The bound still covers the truth.
TEST(DisplacementMonitor, BoundCoversAShearNextToAWallAtRest) {
  Cloud cloud(9);
  const std::vector<double> x0 = cloud.x, y0 = cloud.y;
  DisplacementMonitor monitor;
  monitor.reset(cloud.grid, cloud.x, cloud.y);
  const double rate = 0.01, wall = -1.2;
  for (int call = 1; call <= 3; ++call) {
    for (std::size_t i = 0; i < cloud.x.size(); ++i)
      cloud.x[i] = x0[i] + call * rate * std::max(y0[i] - wall, 0.0);
    const double bound = monitor.max_closing(cloud.grid, cloud.x, cloud.y, kCutoff, call);
    EXPECT_GE(bound, true_max_closing(x0, y0, cloud.x, cloud.y, kCutoff)) << "call " << call;
    if (call > 1) {
      EXPECT_LT(bound, 1.5 * call * rate * kCutoff) << "call " << call;
    }
  }
}

// Two blocks of particles, one or two empty columns of cells between them, move towards each
// other: no particle between them sees it coming, only the pairs of cells two apart and the
// range of the displacement over all pairs farther apart do. The bound covers the closing.
TEST(DisplacementMonitor, BlocksClosingInAcrossEmptyCellsAreSeen) {
  for (int empty = 1; empty <= 2; ++empty) {
    CellGrid grid(0.0, 10.0, 0.0, 5.0, kCutoff);
    std::vector<double> x0, y0;
    for (int block = 0; block < 2; ++block) {
      const double left = (2 + block * (empty + 1)) * kCutoff;  // the block fills one column
      for (double px = left + 0.5 * kDx; px < left + kCutoff; px += kDx)
        for (double py = kCutoff + 0.5 * kDx; py < 4.0 * kCutoff; py += kDx) {
          x0.push_back(px);
          y0.push_back(py);
        }
    }
    std::vector<std::uint32_t> order, outside;
    grid.sort(x0, y0, order, outside);
    ASSERT_TRUE(outside.empty());
    std::vector<double> xs, ys;
    for (std::uint32_t k : order) xs.push_back(x0[k]), ys.push_back(y0[k]);
    DisplacementMonitor monitor;
    monitor.reset(grid, xs, ys);
    const double split = (2 + 1.0) * kCutoff;     // between the blocks
    const double move = empty == 1 ? 0.2 : 0.65;  // each block, towards the other
    std::vector<double> x = xs;
    for (double& px : x) px += px < split ? move : -move;
    const double truth = true_max_closing(xs, ys, x, ys, kCutoff);
    EXPECT_GT(truth, kSkin) << empty;  // the case tested: pairs came within the support
    EXPECT_GE(monitor.max_closing(grid, x, ys, kCutoff, 1.0), truth) << empty;
  }
}

// The build positions are kept relative to each particle's cell; one that is not where the
// grid says (here: moved two cells after the sort) is stored wrongly, and the bound must then
// grow by at least that error instead of hiding it.
TEST(DisplacementMonitor, AParticleOutsideItsCellWidensTheBound) {
  Cloud cloud(7);
  DisplacementMonitor clean;
  clean.reset(cloud.grid, cloud.x, cloud.y);
  // At rest only the fixed point is left: each coordinate of each box spans at most a step
  // (sqrt(2) steps as a vector), and the stored error adds 2 sqrt(2) half steps; 1e-5 for the
  // rounding of the float arithmetic.
  const double step = 2.0 * kCutoff / 65535.0;
  const double at_rest = clean.max_closing(cloud.grid, cloud.x, cloud.y, kCutoff, 1.0);
  EXPECT_LT(at_rest, 2.0 * std::sqrt(2.0) * step + 1e-5);
  cloud.x[0] += 2.0 * kCutoff;  // no longer in its cell's range of the sort
  DisplacementMonitor monitor;
  monitor.reset(cloud.grid, cloud.x, cloud.y);
  EXPECT_GT(monitor.max_closing(cloud.grid, cloud.x, cloud.y, kCutoff, 1.0), 0.5 * kCutoff);
  std::vector<double> fewer(cloud.x.begin(), cloud.x.end() - 1);
  EXPECT_THROW(monitor.reset(cloud.grid, fewer, fewer), std::logic_error);
  // The lists' reach must fit in a cell (pairs of cells farther apart are not examined).
  EXPECT_THROW((void)clean.max_closing(cloud.grid, cloud.x, cloud.y, 1.01 * kCutoff, 1.0),
               std::logic_error);
}

// The stored build positions are rounded to a fixed-point step (2 cells / 65535), and the
// rounding can hide a real displacement: two particles of one cell stored half a step off in
// opposite directions, one moved by a step, look as if neither had moved. The bound adds
// the storage error it measured and still covers the real displacement.
TEST(DisplacementMonitor, BoundCoversWhatTheStoredRoundingHides) {
  CellGrid grid(0.0, 1.0, 0.0, 1.0, 1.0);  // one cell; its fixed-point range starts at -0.5
  const double step = 2.0 / 65535.0;
  std::vector<double> x = {-0.5 + (20000.5 + 1e-3) * step,   // stored half a step up
                           -0.5 + (30000.5 - 1e-3) * step};  // stored half a step down
  std::vector<double> y = {-0.5 + 40000 * step, -0.5 + 40000 * step};
  std::vector<std::uint32_t> order, outside;
  grid.sort(x, y, order, outside);
  ASSERT_EQ(order, (std::vector<std::uint32_t>{0, 1}));
  DisplacementMonitor monitor;
  monitor.reset(grid, x, y);
  x[0] += step;  // the real relative displacement: one step
  EXPECT_GE(monitor.max_closing(grid, x, y, 1.0, 1.0), step);
  EXPECT_LT(monitor.max_closing(grid, x, y, 1.0, 2.0), 3.0 * step);  // and not much more
}

// The safety property: with rough displacement fields (a shear, a compression, a rotation, a
// wall at rest, random kicks), as long as the monitor says "keep the lists", the bound covers
// the true closing and every pair closer than the kernel support is in the lists.
TEST(DisplacementMonitor, NoPairWithinTheSupportIsMissedWhileTheListsAreKept) {
  struct Field {
    const char* name;
    double shear, squeeze, turn, wall;  // per step; wall: particles below it stay put
  };
  for (const Field& field :
       {Field{"shear", 0.05, 0.0, 0.0, -9.0}, Field{"squeeze and turn", 0.0, 0.004, 0.001, -9.0},
        Field{"shear over a wall", 0.05, 0.0, 0.0, -1.0}}) {
    Cloud cloud(11);
    std::vector<double> x0 = cloud.x, y0 = cloud.y;
    DisplacementMonitor monitor;
    monitor.reset(cloud.grid, cloud.x, cloud.y);
    std::mt19937 rng(42);
    std::normal_distribution<double> kick(0.0, 0.02 * kSkin);
    const std::size_t n = cloud.x.size();
    int kept_steps = 0, rebuilds = 0, since_build = 0;
    for (int step = 0; step < 60; ++step) {
      for (std::size_t i = 0; i < n; ++i) {
        if (cloud.y[i] < field.wall) continue;
        const double px = cloud.x[i] - 10.0, py = cloud.y[i];
        cloud.x[i] += field.shear * kSkin * (1.0 + py - std::max(field.wall, -3.0)) -
                      field.squeeze * px - field.turn * py + kick(rng);
        cloud.y[i] += field.turn * px + kick(rng);
      }
      ++since_build;
      const double bound = monitor.max_closing(cloud.grid, cloud.x, cloud.y, kCutoff, since_build);
      ASSERT_GE(bound, true_max_closing(x0, y0, cloud.x, cloud.y, kCutoff))
          << field.name << ", step " << step;
      if (bound > kSkin) {
        cloud.build();
        x0 = cloud.x, y0 = cloud.y;
        monitor.reset(cloud.grid, cloud.x, cloud.y);
        ++rebuilds;
        since_build = 0;
        continue;
      }
      ++kept_steps;
      const auto listed = cloud.listed();
      for (std::size_t i = 0; i < n; ++i) {
        for (std::size_t j = i + 1; j < n; ++j) {
          if (cloud.distance(i, j) >= kSupport) continue;
          ASSERT_EQ(listed.count({static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(j)}),
                    1u)
              << field.name << ", step " << step << ": pair " << i << ", " << j
              << " within 3h missing";
        }
      }
    }
    EXPECT_GT(kept_steps, 30) << field.name;  // kept lists were exercised, not rebuilds only
    EXPECT_GT(rebuilds, 1) << field.name;
  }
}

}  // namespace
}  // namespace adrsph
