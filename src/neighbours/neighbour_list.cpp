#include "neighbours/neighbour_list.hpp"

#include <type_traits>

namespace adrsph {

namespace {
constexpr std::integral_constant<int, 1> kOneRing{};  // the 3x3 cells around a particle
}  // namespace

void NeighbourList::build(const CellGrid& grid, std::span<const double> x,
                          std::span<const double> y, double cutoff, std::uint32_t padding_index) {
  const std::size_t n = padding_index;  // real particles are [0, n)
  const double rc2 = cutoff * cutoff;
  count_.assign(n, 0);
  offset_.assign(n + 1, 0);
  std::size_t real_total = 0;
#pragma omp parallel for schedule(static) reduction(+ : real_total)
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t cnt = 0;
    const double xi = x[i], yi = y[i];
    grid.for_each_near(xi, yi, kOneRing, [&](std::uint32_t j) {
      const double dx = xi - x[j], dy = yi - y[j];
      cnt += (j != i && dx * dx + dy * dy < rc2) ? 1u : 0u;
    });
    count_[i] = cnt;
    real_total += cnt;
  }
  for (std::size_t i = 0; i < n; ++i)
    offset_[i + 1] = offset_[i] + (count_[i] + kPad - 1) / kPad * kPad;
  // Growing past the capacity adds ~3% headroom, not std::vector's doubling (the lists are
  // the second largest block of a run, after the particle arrays).
  if (offset_[n] > index_.capacity()) index_.reserve(offset_[n] + offset_[n] / 32);
  index_.resize(offset_[n]);
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    std::uint32_t k = offset_[i];
    const double xi = x[i], yi = y[i];
    grid.for_each_near(xi, yi, kOneRing, [&](std::uint32_t j) {
      const double dx = xi - x[j], dy = yi - y[j];
      if (j != i && dx * dx + dy * dy < rc2) index_[k++] = j;
    });
    for (; k < offset_[i + 1]; ++k) index_[k] = padding_index;
  }
  mean_ = n ? static_cast<double>(real_total) / static_cast<double>(n) : 0.0;
}

}  // namespace adrsph
