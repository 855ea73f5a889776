// Cached neighbour lists in CSR form, built from the cell grid with a cut-off slightly above
// the kernel support (3h + skin) and reused until particles may have moved skin/2.
// A pass's pair loop runs over a row padded to a multiple of kPad with the padding particle,
// so that it runs whole SIMD vectors without a scalar tail.
//
// Entries are 16-bit offsets j - i where every pair allows it, 32-bit indices otherwise. The
// particles are sorted along a Morton curve, so a neighbour is close to i in the arrays too:
// in the reactor channel the largest offset is 1,312 / 2,330 / 8,691 at dx = 0.5 / 0.25 /
// 0.125 mm, and the lists take half the bytes (perf/README.md, section 3.9). A scene where
// some pair is farther apart in the order (the channel at dx = 0.0625 mm: 33,537; a square
// domain of more than ~65,000 particles) gets 32-bit indices instead, decided at
// each build (and one with a row longer than kMaxRow entries). The passes see either form
// through one call, `with_indices`, taken once per pass outside its loops: the loop body is
// compiled for each form and carries no branch on it.
//
// A build visits the ~89 candidates of the 3 x 3 cells around each particle. The first build
// (and the 32-bit form) visits them twice: count the rows, then fill them. Later builds of the
// 16-bit form visit them once, each thread storing its rows in its part of the entries' capacity
// (sized from the previous build's rows), after which the parts are moved together: the build
// takes 0.6x the time of two visits (perf/README.md, section 3.19).
//
// The 16-bit form stores the real entries only and pads a row when it expands it into the
// indices a pair loop reads (the padding is not stored: 1.6 entries per particle in the
// reactor channel at fine resolution, where most rows hold 31 or 32 entries).
// The 32-bit form stores its rows padded and the pair loop reads them in place (a row may be
// longer than the expansion buffer).
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "neighbours/cell_grid.hpp"

namespace adrsph {

class NeighbourList {
 public:
  static constexpr std::uint32_t kPad = 8;
  static constexpr std::int32_t kMaxOffset = std::numeric_limits<std::int16_t>::max();

  enum class Width { automatic, wide };  // wide: 32-bit indices whatever the offsets

  // The most entries a particle may have in the 16-bit form (a row is expanded into a buffer
  // of this size on the stack); a scene with a longer row gets the 32-bit form.
  static constexpr std::uint32_t kMaxRow = 512;
  // The size of the buffer a row is expanded into: the padding is written as one vector of
  // kPad entries from the row's end (a test of k < len in the expansion loop makes g++ -O3
  // split it in two loops with scalar tails: 7% more instructions in the force pass, perf
  // guard).
  static constexpr std::uint32_t kRowBuffer = kMaxRow + kPad;

  // The entries a pair loop runs over for a row of `count` real ones: whole vectors.
  static constexpr std::uint32_t padded(std::uint32_t count) {
    return (count + kPad - 1) / kPad * kPad;
  }

  // The two forms. A pass takes, for each particle i, row(i, kb, ke, buffer) (through row_of,
  // below): the indices of its entries [kb, ke) followed by the padding particle up to
  // padded(ke - kb) entries, then runs its pair loop over that array. The pair loops are thus the
  // same code for both forms: g++ 12 does not vectorise a pair loop that reads 16-bit entries
  // itself (it picks 16 lanes from them, and has no gather of 16 doubles), which ran 2.2x the
  // instructions (perf guard). 16-bit form: i + offset expanded into `buffer` (kRowBuffer entries,
  // one short vector loop), then the padding. The loop reads up to kPad - 1 entries past the row's
  // end (the next row's, or the kSlack entries the array holds past the last row), which the
  // padding overwrites.
  struct Offsets {
    const std::int16_t* entries;
    std::uint32_t padding;
    const std::uint32_t* row(std::size_t i, std::uint32_t kb, std::uint32_t ke,
                             std::uint32_t* buffer) const;  // (below the class)
  };
  static constexpr std::uint32_t kSlack = kPad;
  // 32-bit form: the indices themselves, rows stored padded (ke - kb a multiple of kPad).
  struct Indices {
    const std::uint32_t* entries;
    const std::uint32_t* row(std::size_t, std::uint32_t kb, std::uint32_t, std::uint32_t*) const {
      return entries + kb;
    }
  };

  // Particle i's row as a pass reads it: row_of(form, i, buffer) with `buffer` of kRowBuffer
  // entries on the pass's stack (the 16-bit form expands the row into it).
  struct Row {
    const std::uint32_t* index;  // the neighbours, then the padding particle up to `whole`
    std::uint32_t first;         // the position of its first stored entry (arrays per entry)
    std::uint32_t stored;        // its stored entries: the real ones (16-bit), padded (32-bit)
    std::uint32_t whole;         // padded(stored): the entries a pair loop runs over
  };
  template <class Form>
  Row row_of(const Form& form, std::size_t i, std::uint32_t* buffer) const {
    const std::uint32_t kb = begin(i), ke = end(i);
    return {form.row(i, kb, ke, buffer), kb, ke - kb, padded(ke - kb)};
  }

  // Particles of one class whose rows leave each other out: where kind[i] == among, row i lists
  // no j with kind[j] == among, or nothing at all (whole_row). The reactor's walls: only the
  // boundary pass reads a wall's row, and it samples no wall (a third of a wall's row, which it
  // weighted by zero); a prescribed flow has no boundary pass and reads no wall's row.
  // Default: none.
  struct Omit {
    const std::uint8_t* kind;  // nullptr: no rule
    std::uint8_t among;
    bool whole_row;
  };

  // Build for particles already sorted by `grid` (grid.sort() then permuted). Self excluded.
  void build(const CellGrid& grid, std::span<const double> x, std::span<const double> y,
             double cutoff, std::uint32_t padding_index, Width width = Width::automatic,
             Omit omit = {nullptr, 0, false});

  // pass(form) with form an Offsets or an Indices of this list; the entries of particle i are
  // [begin(i), end(i)): its real ones (16-bit form), padded to a multiple of kPad (32-bit form).
  template <class Pass>
  decltype(auto) with_indices(Pass&& pass) const {
    return wide_ ? pass(Indices{index_.data()}) : pass(Offsets{offset16_.data(), padding_});
  }

  // Whether the last build took one pass over the candidates (see build_one_pass) or two.
  bool one_pass() const { return one_pass_; }

  std::uint32_t begin(std::size_t i) const { return offset_[i]; }
  std::uint32_t end(std::size_t i) const { return offset_[i + 1]; }
  std::size_t total() const { return offset_.empty() ? 0 : offset_.back(); }
  bool wide() const { return wide_; }
  double mean_neighbours() const { return mean_; }  // real neighbours (without padding)
  // Give the entries and row starts back (the end of a run: nothing is stepped after it);
  // mean_neighbours() keeps its value. A build makes them anew.
  void release() {
    std::vector<std::uint32_t>().swap(offset_);
    std::vector<std::int16_t>().swap(offset16_);
    std::vector<std::uint32_t>().swap(index_);
  }
  std::size_t bytes() const {
    return (offset_.capacity() + index_.capacity()) * sizeof(std::uint32_t) +
           offset16_.capacity() * sizeof(std::int16_t);
  }

 private:
  // The 16-bit form in one pass over the candidates, each thread storing its rows in a region
  // of the entries sized from the previous build's rows, then the regions moved together.
  // False (and the list to be built in two passes: count, then fill) at the first build, for
  // the 32-bit form, or when a thread's rows outgrew its region.
  bool build_one_pass(const CellGrid& grid, std::span<const double> x, std::span<const double> y,
                      double rc2, std::size_t n, Omit omit);

  std::vector<std::uint32_t> offset_;   // CSR row starts, size n + 1
  std::vector<std::int16_t> offset16_;  // entries, 16-bit form
  std::vector<std::uint32_t> index_;    // entries, 32-bit form (empty while 16-bit serves)
  std::uint32_t padding_ = 0;           // index of the padding particle
  bool wide_ = false;
  bool one_pass_ = false;
  double mean_ = 0.0;
};

inline const std::uint32_t* NeighbourList::Offsets::row(std::size_t i, std::uint32_t kb,
                                                        std::uint32_t ke,
                                                        std::uint32_t* buffer) const {
  // Locals: a store to buffer may alias the member `padding` (both uint32), and g++ then
  // reloads it in the loop and does not vectorise it.
  const std::int16_t* e = entries + kb;
  const std::uint32_t pad = padding, len = ke - kb, whole = padded(len);
  const auto base = static_cast<std::int32_t>(i);
#pragma omp simd
  for (std::uint32_t k = 0; k < whole; ++k)  // past the row: the next row's entries or the slack
    buffer[k] = static_cast<std::uint32_t>(base + std::int32_t{e[k]});
  std::fill_n(buffer + len, kPad, pad);  // one vector store over what was read past the row
  return buffer;
}

}  // namespace adrsph
