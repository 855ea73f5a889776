// A run's residence-time distribution against the transient finite-volume reference of its
// case (docs/rtd.md, "Against the transient reference"): the reference's outlet series
// (REF_DIR/outlet.csv of `adrsph reference --transient`), its feed-corrected moments, and the
// shape distance of the two normalised responses on the run's samples. Pure functions.
#pragma once

#include <string>
#include <vector>

#include "adrsph/case.hpp"
#include "adrsph/probes.hpp"
#include "analysis/rtd.hpp"

namespace adrsph::analysis {

struct RtdAgainst {
  // The reference's own series: its samples, the moments of its excess over its base (trapezoid
  // rule on its samples, rtd.hpp) and, corrected for its feed's moments, its vessel's.
  std::size_t samples = 0;
  double t_first = 0.0, t_last = 0.0;
  FeedMoments feed;
  CurveMoments outlet;
  double mean_residence_time = 0.0;  // outlet.mean - feed.mean [s]
  double variance = 0.0;             // outlet.variance - feed.variance [s^2]
  double recovery = 0.0;             // outlet.area / feed.amount

  // At the run's sample times, linear in t between the reference's samples: C_ref and its
  // normalised response E_ref = (C_ref - base) / outlet.area.
  std::vector<double> c_ref, e_ref;
  // int |E_run - E_ref| dt by the trapezoid rule on the run's samples: 0 for the same shape,
  // at most 2 for non-negative curves.
  double l1 = 0.0;
  double mean_over_reference_minus_1 = 0.0;      // run t_m / reference t_m - 1
  double variance_over_reference_minus_1 = 0.0;  // run s^2 / reference s^2 - 1

  // "key: run V, reference W" for every physical key where the two cases differ.
  std::vector<std::string> case_differences;
};

// `reference_case` is the case the reference was solved for (its base and feed moments).
// Throws RtdInputError (Source::outlet) when the reference has fewer than 3 samples, no area
// of its feed's sign, or samples that do not cover the run's [t_first, t_last].
RtdAgainst against_reference(const Rtd& run, const Case& run_case,
                             const std::vector<OutletRow>& reference, const Case& reference_case);

}  // namespace adrsph::analysis
