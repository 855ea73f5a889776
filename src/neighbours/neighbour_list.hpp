// Cached neighbour lists in CSR form, built from the cell grid with a cut-off slightly above
// the kernel support (3h + skin) and reused until particles may have moved skin/2.
// Each particle's list is padded to a multiple of kPad with the padding particle's index,
// so the inner loops run whole SIMD vectors without a scalar tail.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "neighbours/cell_grid.hpp"

namespace adrsph {

class NeighbourList {
 public:
  static constexpr std::uint32_t kPad = 8;

  // Build for particles already sorted by `grid` (grid.sort() then permuted). Self excluded.
  void build(const CellGrid& grid, std::span<const double> x, std::span<const double> y,
             double cutoff, std::uint32_t padding_index);

  std::uint32_t begin(std::size_t i) const { return offset_[i]; }
  std::uint32_t end(std::size_t i) const { return offset_[i + 1]; }
  const std::uint32_t* data() const { return index_.data(); }
  std::size_t total() const { return index_.size(); }
  double mean_neighbours() const { return mean_; }  // real neighbours (without padding)
  std::size_t bytes() const {
    return (offset_.capacity() + index_.capacity()) * sizeof(std::uint32_t);
  }

 private:
  std::vector<std::uint32_t> offset_;  // size n + 1
  std::vector<std::uint32_t> index_;
  std::vector<std::uint32_t> count_;
  double mean_ = 0.0;
};

}  // namespace adrsph
