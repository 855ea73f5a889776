// The paper's table 3 (docs/benchmark.md, section 4): relative error of the section average at
// x = 25, 50, 100, fine resolution, for the modern and the conventional scheme.
#include <cmath>

#include "analysis/compare.hpp"

namespace adrsph::analysis {

std::optional<PaperRow> paper_table3_row(double pe) {
  static constexpr PaperRow kRows[] = {
      {10.0, {0.0074, 0.0122, 0.0176}, {0.0094, 0.0187, 0.0379}},
      {1000.0, {0.0108, 0.0142, 0.0226}, {0.0088, 0.0142, 0.0334}},
      {100000.0, {0.0155, 0.0025, 0.0082}, {0.0026, 0.0044, 0.0302}},
  };
  for (const PaperRow& r : kRows)
    if (std::abs(pe - r.pe) <= 0.01 * r.pe) return r;
  return std::nullopt;
}

}  // namespace adrsph::analysis
