#include "neighbours/neighbour_list.hpp"

#include <omp.h>

#include <algorithm>
#include <cstring>

namespace adrsph {

namespace {
// Growing past the capacity adds ~3% headroom, not std::vector's doubling (the lists are the
// second largest block of a run, after the particle arrays); the other form is released.
// `total` entries and the slack a 16-bit row's expansion reads past the last row, with at least
// `spare` entries of capacity beyond them.
template <class T, class U>
void size_entries(std::vector<T>& used, std::vector<U>& other, std::size_t total,
                  std::size_t spare = 0) {
  const std::size_t size = total + NeighbourList::kSlack;
  if (size + spare > used.capacity()) {  // the old entries are rewritten: freed first, not copied
    std::vector<T>().swap(used);
    used.reserve(size + std::max(spare, total / 32));
  }
  used.resize(size);
  std::vector<U>().swap(other);
}

// The capacity a one-pass build wants beyond the entries it expects: rows grow by well under 1%
// from one build to the next (a build follows the last one by a few steps).
std::size_t one_pass_spare(std::size_t total) {
  return total / 128 + NeighbourList::kMaxRow;
}

// The capacity the first build leaves beyond its entries: a run that starts from the lattice
// lists ~9% more pairs a few steps later, once the lattice has disordered (the coarse reactor's
// 10-step probe, perf/README.md section 3.19), and a one-pass build that outgrows its capacity
// is a build and a half. The capacity is the same as that of a list regrown after such a miss.
std::size_t first_build_spare(std::size_t total) {
  return total / 8 + NeighbourList::kMaxRow;
}

// 1 if j belongs in the row of i (within the cut-off, not i itself), else 0. As arithmetic:
// `j != i && d2 < rc2` is compiled to two branches, and in a run the distance test follows no
// pattern (the self pair has d2 = 0 and is taken off by the subtraction).
inline std::uint32_t in_row(std::size_t i, std::uint32_t j, double d2, double rc2) {
  return static_cast<std::uint32_t>(d2 < rc2) - static_cast<std::uint32_t>(j == i);
}

// The candidates of the particles of one cell: the particle ranges of the 3 x 3 cells around
// it, in the order CellGrid::for_each_near visits them, with two ranges that follow each other
// in that order and in memory joined into one (two cells of a Morton pair, and empty cells
// dropped). The candidates come in the same order, in ~6 loops instead of 9, and the particles
// of a cell (consecutive after the sort) take the ranges of the one before them.
struct CandidateRanges {
  int cx = -2, cy = -2;  // the cell the ranges are for (-2: none)
  int count = 0;
  std::uint32_t first[9], last[9];

  void set(const CellGrid& grid, double x, double y) {
    const int ax = grid.cell_x(x), ay = grid.cell_y(y);
    if (ax == cx && ay == cy) return;
    cx = ax, cy = ay, count = 0;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int r = grid.rank(cx + dx, cy + dy);
        if (r < 0) continue;
        const std::uint32_t a = grid.cell_start(r), b = grid.cell_start(r + 1);
        if (a == b) continue;
        if (count > 0 && last[count - 1] == a) {
          last[count - 1] = b;
        } else {
          first[count] = a, last[count] = b;
          ++count;
        }
      }
    }
  }
};

// visit(j, take) for each candidate j of particle i's row, take = 1 if j belongs in it, else 0
// (in_row, and the Omit rule; none at all in a row it empties), j in the order
// CellGrid::for_each_near gives. The rule's test of kind[j] is made only in the rows it applies
// to (a branch per row: walls come in runs along the curve). `near`: the calling thread's
// ranges (of the last cell it visited).
template <class Visit>
inline void for_each_candidate(const CellGrid& grid, std::span<const double> x,
                               std::span<const double> y, double rc2, std::size_t i,
                               NeighbourList::Omit omit, CandidateRanges& near, Visit&& visit) {
  const double xi = x[i], yi = y[i];
  near.set(grid, xi, yi);
  // Bounds read into locals: visit() stores through pointers g++ cannot tell apart from them.
  const int count = near.count;
  auto scan = [&](auto keep) {  // keep(j): all bits set unless the rule leaves j out (0)
    for (int c = 0; c < count; ++c) {
      const std::uint32_t a = near.first[c], b = near.last[c];
      for (std::uint32_t j = a; j < b; ++j) {
        const double dx = xi - x[j], dy = yi - y[j];
        visit(j, in_row(i, j, dx * dx + dy * dy, rc2) & keep(j));
      }
    }
  };
  if (omit.kind != nullptr && omit.kind[i] == omit.among) {
    if (omit.whole_row) return;  // an empty row
    scan([kind = omit.kind, among = omit.among](std::uint32_t j) {
      return 0u - static_cast<std::uint32_t>(kind[j] != among);
    });
  } else {
    scan([](std::uint32_t) { return ~0u; });  // (the mask then costs nothing)
  }
}

// Fill row i of the CSR with entry(i, j), j its neighbours in the order the cells give them,
// then pad it to its end with `pad` (rows of the 16-bit form end with their last entry). Every
// candidate is stored and the row end advances by in_row, with no branch on it (a branch ran the
// build 2.2x slower on a run's particles than on the lattice, BM_NeighbourListDisordered). The row
// is assembled in a buffer of its thread and copied (a store past the row's end would land in the
// next row, which may be another thread's). (A function, not a generic lambda: clang does not
// accept an OpenMP loop in a generic lambda that reads the enclosing function's locals.)
template <class T, class Entry>
void fill_rows(const CellGrid& grid, std::span<const double> x, std::span<const double> y,
               double rc2, NeighbourList::Omit omit, const std::vector<std::uint32_t>& offset,
               std::uint32_t longest, T* entries, Entry entry, T pad) {
  const std::size_t n = offset.size() - 1;
#pragma omp parallel
  {
    std::vector<T> buffer(longest + 1);  // a row holds at most `longest` entries, +1 store
    T* row = buffer.data();
    CandidateRanges near;
#pragma omp for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      std::uint32_t k = 0;
      for_each_candidate(grid, x, y, rc2, i, omit, near, [&](std::uint32_t j, std::uint32_t take) {
        row[k] = entry(i, j);
        k += take;
      });
      T* out = entries + offset[i];
      std::copy_n(row, k, out);
      std::fill(out + k, entries + offset[i + 1], pad);
    }
  }
}
}  // namespace

bool NeighbourList::build_one_pass(const CellGrid& grid, std::span<const double> x,
                                   std::span<const double> y, double rc2, std::size_t n,
                                   Omit omit) {
  const std::size_t n_before = offset_.empty() ? 0 : offset_.size() - 1;
  if (wide_ || n == 0 || n_before == 0) return false;
  // Each thread's share of the particles, [first[t], first[t + 1]), and of the entries' capacity,
  // [region[t], region[t + 1]): in proportion to the entries the same index range held at the
  // previous build (the order is spatial).
  const auto shares = static_cast<std::size_t>(omp_get_max_threads());
  std::vector<std::size_t> first(shares + 1), region(shares + 1, 0), length(shares, 0);
  std::vector<double> expected(shares);
  double expected_total = 0.0;
  for (std::size_t t = 0; t <= shares; ++t) first[t] = n * t / shares;
  for (std::size_t t = 0; t < shares; ++t) {
    const std::size_t a = std::min(first[t], n_before), b = std::min(first[t + 1], n_before);
    const double per_particle =
        b > a ? static_cast<double>(offset_[b] - offset_[a]) / static_cast<double>(b - a) : mean_;
    expected[t] = per_particle * static_cast<double>(first[t + 1] - first[t]);
    expected_total += expected[t];
  }
  // Without enough spare capacity, two passes, which grow the entries (this build's list is
  // not stored twice, and a failed one-pass build is rare).
  const std::size_t capacity = std::max<std::size_t>(offset16_.capacity(), kSlack) - kSlack;
  const auto wanted = static_cast<std::size_t>(expected_total);
  if (wanted + one_pass_spare(wanted) > capacity) return false;
  double cumulative = 0.0;
  for (std::size_t t = 0; t + 1 < shares; ++t) {
    cumulative += expected[t];
    region[t + 1] = static_cast<std::size_t>(static_cast<double>(capacity) * cumulative /
                                             std::max(expected_total, 1.0));
  }
  region[shares] = capacity;
  offset_.resize(n + 1);
  offset_[0] = 0;
  offset16_.resize(capacity + kSlack);  // within its capacity
  std::int16_t* const entries = offset16_.data();
  std::uint32_t* const row_end = offset_.data() + 1;
  std::uint32_t longest = 0;
  std::int64_t far = 0;
  int missed = 0;  // a share outgrew its region
  const int team = static_cast<int>(shares);
#pragma omp parallel num_threads(team) reduction(max : longest, far, missed)
  {
    // Indices, not offsets, so that the range of the row can be checked before it is stored;
    // a row longer than kMaxRow keeps overwriting its last entry (and is not stored).
    std::uint32_t row[kMaxRow + 1];
    CandidateRanges near;
    const auto threads = static_cast<std::size_t>(omp_get_num_threads());
    for (auto t = static_cast<std::size_t>(omp_get_thread_num()); t < shares; t += threads) {
      std::size_t at = region[t];
      for (std::size_t i = first[t]; i < first[t + 1]; ++i) {
        std::uint32_t k = 0;
        for_each_candidate(grid, x, y, rc2, i, omit, near,
                           [&](std::uint32_t j, std::uint32_t take) {
                             row[std::min(k, kMaxRow)] = j;
                             k += take;
                           });
        longest = std::max(longest, k);
        if (padded(k) > kMaxRow || at + k > region[t + 1]) {
          missed = 1;
          break;
        }
        auto lo = static_cast<std::uint32_t>(i), hi = lo;
        for (std::uint32_t m = 0; m < k; ++m) lo = std::min(lo, row[m]), hi = std::max(hi, row[m]);
        const auto ii = static_cast<std::int64_t>(i);
        far = std::max({far, ii - std::int64_t{lo}, std::int64_t{hi} - ii});
        for (std::uint32_t m = 0; m < k; ++m)
          entries[at + m] = static_cast<std::int16_t>(static_cast<std::int64_t>(row[m]) - ii);
        at += k;
        row_end[i] = static_cast<std::uint32_t>(at);
      }
      length[t] = at - region[t];
    }
  }
  if (missed || far > kMaxOffset) return false;
  // Close the gaps between the shares: each moves down to the end of the one before it.
  std::size_t end = length[0];
  for (std::size_t t = 1; t < shares; ++t) {
    const std::size_t shift = region[t] - end;
    std::memmove(entries + end, entries + region[t], length[t] * sizeof(std::int16_t));
    for (std::size_t i = first[t]; i < first[t + 1]; ++i)
      row_end[i] -= static_cast<std::uint32_t>(shift);
    end += length[t];
  }
  offset16_.resize(end + kSlack);
  mean_ = static_cast<double>(end) / static_cast<double>(n);
  return true;
}

void NeighbourList::build(const CellGrid& grid, std::span<const double> x,
                          std::span<const double> y, double cutoff, std::uint32_t padding_index,
                          Width width, Omit omit) {
  const std::size_t n = padding_index;  // real particles are [0, n)
  const double rc2 = cutoff * cutoff;
  padding_ = padding_index;
  const bool first_build = offset_.empty();
  one_pass_ = width == Width::automatic && build_one_pass(grid, x, y, rc2, n, omit);
  if (one_pass_) return;
  offset_.assign(n + 1, 0);
  std::size_t real_total = 0;
  std::int64_t far = 0;       // the largest |j - i| of a listed pair
  std::uint32_t longest = 0;  // the longest row
  CandidateRanges near;
#pragma omp parallel for schedule(static) firstprivate(near) reduction(+ : real_total) \
    reduction(max : far, longest)
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t cnt = 0, lo = static_cast<std::uint32_t>(i), hi = lo;
    for_each_candidate(grid, x, y, rc2, i, omit, near, [&](std::uint32_t j, std::uint32_t take) {
      // Arithmetic and selects, not branches (see fill_rows); a candidate out of range
      // counts as i itself for the offset range.
      const std::uint32_t m = take ? j : static_cast<std::uint32_t>(i);
      cnt += take;
      lo = std::min(lo, m);
      hi = std::max(hi, m);
    });
    offset_[i + 1] = cnt;  // summed below
    longest = std::max(longest, cnt);
    real_total += cnt;
    const auto ii = static_cast<std::int64_t>(i);
    far = std::max({far, ii - static_cast<std::int64_t>(lo), static_cast<std::int64_t>(hi) - ii});
  }
  wide_ = width == Width::wide || far > kMaxOffset || padded(longest) > kMaxRow;
  if (wide_)  // stored padded (the header)
    for (std::size_t i = 0; i < n; ++i) offset_[i + 1] = padded(offset_[i + 1]);
  for (std::size_t i = 0; i < n; ++i) offset_[i + 1] += offset_[i];
  if (wide_) {
    size_entries(index_, offset16_, offset_[n]);
    fill_rows(
        grid, x, y, rc2, omit, offset_, longest, index_.data(),
        [](std::size_t, std::uint32_t j) { return j; }, padding_index);
  } else {
    size_entries(offset16_, index_, offset_[n],
                 first_build ? first_build_spare(offset_[n]) : one_pass_spare(offset_[n]));
    fill_rows(
        grid, x, y, rc2, omit, offset_, longest, offset16_.data(),
        [](std::size_t i, std::uint32_t j) {
          return static_cast<std::int16_t>(static_cast<std::int64_t>(j) -
                                           static_cast<std::int64_t>(i));
        },
        std::int16_t{0});  // (no padding stored)
  }
  mean_ = n ? static_cast<double>(real_total) / static_cast<double>(n) : 0.0;
}

}  // namespace adrsph
