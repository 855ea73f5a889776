// The outlet-series comparison of `adrsph compare` against a transient reference
// (analysis/outlet_compare.hpp): the excursion's integral, peak, L1 and largest distance.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "analysis/outlet_compare.hpp"

namespace adrsph::analysis {
namespace {

using ::testing::HasSubstr;

// A pulse (or, with sign -1, a dip) on a base: base + sign * scale * exp(-((t - 0.7) / 0.1)^2),
// sampled every dt from 0 to t_end.
std::vector<OutletRow> series(double base, double sign, double scale, double dt, double t_end) {
  std::vector<OutletRow> rows;
  for (int i = 0; i * dt <= t_end + 1e-12; ++i) {
    const double t = i * dt, g = std::exp(-std::pow((t - 0.7) / 0.1, 2));
    rows.push_back({t, base + sign * scale * g, 0.0});
  }
  return rows;
}

// A run 1% above the reference's excursion, on a dip from a base of 1 (the run's start sits
// at the base too): every relative figure is 1%, the peaks are the dip's, at t = 0.7 s.
TEST(OutletCompare, ScaledExcursionGivesItsScaleEverywhere) {
  const auto ref = series(1.0, -1.0, 0.2, 0.005, 3.0);
  const auto run = series(1.0, -1.0, 0.202, 0.01, 2.0);  // coarser, shorter: interpolated
  const OutletSeriesError e = outlet_series_error("B", run, ref);
  EXPECT_EQ(e.samples, 201u);
  EXPECT_NEAR(e.area_error, 0.01, 1e-3);  // the reference interpolated at the run's samples
  EXPECT_NEAR(e.l1, 0.01, 1e-3);
  EXPECT_NEAR(e.max_error, 0.01, 1e-3);
  EXPECT_NEAR(e.run_peak, -0.202, 1e-9);
  EXPECT_NEAR(e.ref_peak, -0.2, 1e-9);
  EXPECT_NEAR(e.run_peak_t, 0.7, 1e-9);
  EXPECT_LT(e.ref_area, 0.0);             // a dip
  ASSERT_TRUE(e.end_offset.has_value());  // both back at the base of 1
  EXPECT_NEAR(*e.end_offset, 0.0, 1e-12);
  const std::string md = outlet_compare_markdown("run", "ref", {e});
  EXPECT_THAT(md, HasSubstr("| B | 201 |"));
  EXPECT_THAT(md, HasSubstr("1.00%"));
}

// A run late by 0.05 s: L1 measures the shape, the areas still agree.
TEST(OutletCompare, ShiftIsSeenByL1NotByTheArea) {
  const auto ref = series(0.0, 1.0, 1.0, 0.005, 3.0);
  auto run = ref;
  for (auto& r : run) r.c_flow = std::exp(-std::pow((r.t - 0.75) / 0.1, 2));
  run.front().c_flow = 0.0;
  const OutletSeriesError e = outlet_series_error("", run, ref);
  EXPECT_NEAR(e.area_error, 0.0, 1e-6);
  EXPECT_GT(e.l1, 0.4);  // exp(-1/4) apart at the peak: L1 = 2 erf(0.25) = 0.55
  EXPECT_LT(e.l1, 0.7);
  EXPECT_NEAR(e.run_peak_t - e.ref_peak_t, 0.05, 1e-9);
  EXPECT_FALSE(e.end_offset.has_value());  // the reference ends at 0
}

// A run whose level sits 0.5% below the reference's after the dip (a steadily fed species
// diluted): the end offset names it, and the excursion's integral carries it.
TEST(OutletCompare, OffsetLevelIsReportedAtTheEnd) {
  const auto ref = series(1.0, -1.0, 0.1, 0.01, 3.0);
  auto run = ref;
  for (std::size_t i = 1; i < run.size(); ++i) run[i].c_flow -= 0.005;
  const OutletSeriesError e = outlet_series_error("B", run, ref);
  ASSERT_TRUE(e.end_offset.has_value());
  EXPECT_NEAR(*e.end_offset, -0.005, 1e-9);
  EXPECT_GT(std::abs(e.area_error), 0.5);  // 0.015 over the dip's 0.0177
}

TEST(OutletCompare, ReferenceThatDoesNotCoverTheRunIsRefused) {
  const auto ref = series(0.0, 1.0, 1.0, 0.01, 1.0);
  const auto run = series(0.0, 1.0, 1.0, 0.01, 2.0);
  EXPECT_THROW(
      {
        try {
          outlet_series_error("A", run, ref);
        } catch (const std::invalid_argument& e) {
          EXPECT_THAT(e.what(), HasSubstr("must reach the run's last sample"));
          throw;
        }
      },
      std::invalid_argument);
  const std::vector<OutletRow> flat = {{0.0, 1.0, 1.0}, {1.0, 1.0, 1.0}, {2.0, 1.0, 1.0}};
  EXPECT_THROW(outlet_series_error("A", run, flat), std::invalid_argument);
  EXPECT_THROW(outlet_series_error("A", {run[0], run[1]}, ref), std::invalid_argument);
}

}  // namespace
}  // namespace adrsph::analysis
