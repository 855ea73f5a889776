// The residence-time distribution of a tracer-pulse run (docs/rtd.md): the moments of the
// outlet response to the feed (outlet.csv), corrected for the feed's own moments, against the
// space time V/Q and the Taylor-Aris dispersion model. Pure functions, no I/O.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "adrsph/case.hpp"
#include "adrsph/probes.hpp"
#include "analysis/dispersion_model.hpp"
#include "species/inlet_feed.hpp"

namespace adrsph::analysis {

// Zeroth moment, mean and variance of a sampled curve g(t), all by the trapezoid rule on the
// samples (docs/rtd.md, section 2):
//   area = int g dt,  mean = int t g dt / area,  variance = int (t - mean)^2 g dt / area.
struct CurveMoments {
  double area = 0.0;      // [mol/m^3 s]
  double mean = 0.0;      // [s]
  double variance = 0.0;  // [s^2]
};
CurveMoments curve_moments(const std::vector<double>& t, const std::vector<double>& g);
// int |a - b| dt by the trapezoid rule on the samples.
double l1_distance(const std::vector<double>& t, const std::vector<double>& a,
                   const std::vector<double>& b);

// v(at) linear between the samples (t increasing), held at the end values outside them.
double interpolate(const std::vector<double>& t, const std::vector<double>& v, double at);

// A number in the messages of the analysis: 6 significant digits (%.6g).
std::string rtd_number(double v);

// Input the analysis cannot use. `source` says where the fix belongs: the feed of the case
// (a constant or step feed, a table that does not return to the base) or the outlet series
// (too few samples, no excess).
class RtdInputError : public std::invalid_argument {
 public:
  enum class Source { feed, outlet };
  RtdInputError(Source source, const std::string& what)
      : std::invalid_argument(what), source_(source) {}
  Source source() const { return source_; }

 private:
  Source source_;
};

struct Rtd {
  // Per sample: the time, the measured C_flow at x = L, the normalised outlet response
  // E_out = g / area (g = C_flow - base) and the model's outlet C = base + g_model.
  std::vector<double> t, c_out, e_out, c_model;

  FeedMoments feed;     // of the feed's excess over base (species/inlet_feed.hpp)
  CurveMoments outlet;  // of the measured excess g
  // The vessel: the outlet response is the feed convolved with E(t), and means and variances
  // of a convolution add, so E's moments are the outlet's minus the feed's.
  double mean_residence_time = 0.0;  // t_m = outlet.mean - feed.mean [s]
  double variance = 0.0;             // s^2 = outlet.variance - feed.variance [s^2]
  double space_time = 0.0;           // tau = V / Q = L / U [s]
  double mean_velocity = 0.0;        // U [mm/s] (analysis/dispersion_model.hpp)
  double recovery = 0.0;             // outlet.area / feed.amount: 1 for a conserved tracer
  double tail = 0.0;                 // g(last sample) / max g
  bool truncated = false;            // tail > kTruncatedTail: the moments miss the tail
  static constexpr double kTruncatedTail = 0.01;

  // The Taylor-Aris model; NaN throughout when D = 0 (no model).
  bool has_model = false;
  TaylorAris model;
  double model_area = 0.0;  // int g_model dt on the samples
  // int |g / area - g_model / model_area| dt on the samples: 0 for the same shape, at most 2
  // for two non-negative curves.
  double l1 = 0.0;
  // The model on the channel's own boundary conditions (closed_outlet_excess): its outlet C
  // per sample, its vessel moments (feed-corrected like the run's) and its L1 distance to the
  // run. The run's figures to compare with: V/Q and 2 K L / U^3 hold for the semi-infinite
  // medium only.
  std::vector<double> c_closed;
  double closed_mean = 0.0, closed_variance = 0.0, closed_l1 = 0.0;

  double mean_over_space_time_minus_1() const { return mean_residence_time / space_time - 1.0; }
  // s^2 against the model's 2 K L / U^3.
  double variance_over_model_minus_1() const { return variance / model.residence.variance() - 1.0; }
  double mean_over_closed_minus_1() const { return mean_residence_time / closed_mean - 1.0; }
  double variance_over_closed_minus_1() const { return variance / closed_variance - 1.0; }
};

// Throws RtdInputError (Source::feed) unless the feed is a tracer input of finite amount: a
// pulse, or a table that starts and ends at species.feed.base, with an excess that is not 0.
void check_rtd_feed(const Case& c);
// Throws RtdInputError: check_rtd_feed's, fewer than 3 samples, no area of the feed's sign.
Rtd residence_time_distribution(const std::vector<OutletRow>& rows, const Case& c);

}  // namespace adrsph::analysis
