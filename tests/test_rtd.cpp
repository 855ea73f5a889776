// The residence-time distribution (docs/rtd.md): the inverse Gaussian model against its own
// pdf, the moments of synthetic outlet series against the closed forms, the table feed's
// convolution against the pulse formula, and `adrsph rtd` on run directories made here.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "adrsph/probes.hpp"
#include "analysis/dispersion_model.hpp"
#include "analysis/rtd.hpp"
#include "analysis/rtd_against.hpp"
#include "analysis/rtd_report.hpp"
#include "io_test_util.hpp"
#include "species/inlet_feed.hpp"

namespace adrsph {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;
using analysis::InverseGaussian;

// The benchmark channel (L = 100, R = 5, u_bulk = 100: U = 133.3 mm/s, tau = 0.75 s) at
// D = 10: K = 856.6 mm^2/s, Pe_L = 15.6, sigma = 0.27 s. A conserved tracer pulse of height
// 2 on a base of 0.5 over [0.1, 0.15) s.
Case pulse_case() {
  Case c;
  c.name = "rtd_pulse";
  c.species.k = 0.0;
  c.species.c_in = 2.5;
  c.species.c_init = 0.5;  // the base: no initial contents to wash out
  c.species.feed.shape = FeedShape::pulse;
  c.species.feed.t0 = 0.1;
  c.species.feed.width = 0.05;
  c.species.feed.base = 0.5;
  return c;
}

// The outlet of a run that follows the model exactly, sampled every dt over [0, t_end].
std::vector<OutletRow> model_outlet(const Case& c, double dt, double t_end) {
  const InverseGaussian e = analysis::taylor_aris(c).residence;
  std::vector<OutletRow> rows;
  const long n = std::lround(t_end / dt);
  for (long i = 0; i <= n; ++i) {
    const double t = dt * static_cast<double>(i);
    const double v = c.species.feed.base + analysis::model_outlet_excess(c.species, e, t);
    rows.push_back({t, v, v});
  }
  return rows;
}

// int_0^t pdf by Simpson's rule at every even grid point of [0, t_max] in n (even) steps.
std::vector<double> integrated_pdf(const InverseGaussian& e, double t_max, long n) {
  const double h = t_max / static_cast<double>(n);
  std::vector<double> f(1, 0.0);
  for (long i = 0; i + 2 <= n; i += 2) {
    const double a = h * static_cast<double>(i);
    f.push_back(f.back() + h / 3.0 *
                               (analysis::pdf(e, a) + 4.0 * analysis::pdf(e, a + h) +
                                analysis::pdf(e, a + 2.0 * h)));
  }
  return f;
}

TEST(RtdModel, TaylorArisUsesTheDeliveredMeanVelocity) {
  const analysis::TaylorAris m = analysis::taylor_aris(pulse_case());
  const double u = 400.0 / 3.0;  // 2/3 of u_max = 200 mm/s
  EXPECT_DOUBLE_EQ(m.space_time, 0.75);
  EXPECT_NEAR(m.dispersion, 10.0 + u * u * 100.0 / 2100.0, 1e-9);
  EXPECT_NEAR(m.peclet_length, u * 100.0 / m.dispersion, 1e-12);
  EXPECT_NEAR(m.residence.variance(), 2.0 * m.dispersion * 100.0 / (u * u * u), 1e-15);
  EXPECT_NEAR(m.applicability, 0.75 * 10.0 / 25.0, 1e-15);
  EXPECT_FALSE(m.applies());
}

// F against the integral of E, from a skewed (Pe_L = 0.5) to a sharp (Pe_L = 1e4) curve.
// Simpson on 4e4 steps over [0, 4 mu] resolves even the sharpest (sigma/mu = 0.014, 140
// steps per sigma): its error is far below the 1e-9 asserted.
TEST(RtdModel, CdfIsTheIntegralOfThePdf) {
  for (const double pe : {0.5, 15.6, 1e3, 1e4}) {
    const InverseGaussian e{0.75, 0.75 * pe / 2.0};  // 2 lambda / mu = Pe_L
    const long n = 40000;
    const std::vector<double> f = integrated_pdf(e, 4.0 * e.mean, n);
    for (std::size_t k = 0; k < f.size(); k += 250) {
      const double t = 4.0 * e.mean * 2.0 * static_cast<double>(k) / static_cast<double>(n);
      EXPECT_NEAR(analysis::cdf(e, t), f[k], 1e-9) << "Pe_L " << pe << " t " << t;
    }
  }
}

// At Pe_L = 1e4 the textbook form's exp(2 lambda / mu) = exp(1e4) overflows, and erfc of the
// second term underflows; neither may reach F, which must stay a distribution function.
TEST(RtdModel, CdfDoesNotOverflowAtLargePeclet) {
  ASSERT_TRUE(std::isinf(std::exp(1e4)));
  for (const double pe : {1e4, 1e6}) {
    const InverseGaussian e{1.0, pe / 2.0};
    double last = 0.0;
    for (int i = 0; i <= 4000; ++i) {
      const double f = analysis::cdf(e, 0.8 + 1e-4 * i);
      ASSERT_TRUE(std::isfinite(f)) << pe;
      ASSERT_GE(f, last - 1e-15) << "not monotone at Pe_L " << pe;
      ASSERT_LE(f, 1.0);
      last = f;
    }
    EXPECT_NEAR(last, 1.0, 1e-12);
    // At t = mu, z1 = 0 and z2 = sqrt(2 Pe_L): F(mu) = Phi(0) + scaled_erfc(sqrt(Pe_L)) / 2,
    // and the second term ~ 1 / sqrt(4 pi Pe_L) (1 - 1 / (2 Pe_L)), not 0 as erfc's
    // underflow would make it.
    const double second = (1.0 - 0.5 / pe) / std::sqrt(4.0 * std::numbers::pi * pe);
    EXPECT_NEAR(analysis::cdf(e, 1.0), 0.5 + second, 1e-3 * second) << pe;
  }
  // The scaled erfc continues the direct form across its switch to the asymptotic series.
  EXPECT_NEAR(analysis::scaled_erfc(20.0) / (std::exp(400.0) * std::erfc(20.0)), 1.0, 1e-13);
  EXPECT_NEAR(analysis::scaled_erfc(1e3) * 1e3 * std::sqrt(std::numbers::pi), 1.0 - 5e-7, 1e-12);
}

// Moments of a sampled model outlet (over [0, 8] s; the tail at 8 s is ~1e-15 of the peak),
// at dt = 0.005 s and at a coarse 0.05 s. The trapezoid rule's error is at most
// (dt^2 / 12) int |f''| dt: for these curves about (dt / sigma)^2 / 12 relative (3e-5 and
// 3e-3), the tolerances asserted. (A curve flat at both ends does much better, by the
// Euler-Maclaurin formula.) The feed's w/2 = 0.025 s and w^2/12 = 2.1e-4 s^2 are well above
// the fine tolerance: dropping the feed correction would fail.
TEST(RtdMoments, InverseGaussianOutletGivesTheAnalyticMoments) {
  const Case c = pulse_case();
  const analysis::TaylorAris m = analysis::taylor_aris(c);
  const double mu = 0.75, var = m.residence.variance(), w = c.species.feed.width;
  for (const double dt : {0.005, 0.05}) {
    const double tol = (dt * dt) / (12.0 * var);
    const analysis::Rtd r = analysis::residence_time_distribution(model_outlet(c, dt, 8.0), c);
    EXPECT_NEAR(r.outlet.mean, mu + c.species.feed.t0 + w / 2.0, tol * mu) << dt;
    EXPECT_NEAR(r.outlet.variance, var + w * w / 12.0, tol * var) << dt;
    EXPECT_NEAR(r.mean_residence_time, mu, tol * mu) << dt;
    EXPECT_NEAR(r.variance, var, tol * var) << dt;
    EXPECT_NEAR(r.mean_over_space_time_minus_1(), 0.0, tol) << dt;
    EXPECT_NEAR(r.variance_over_model_minus_1(), 0.0, tol) << dt;
    EXPECT_NEAR(r.recovery, 1.0, tol) << dt;
    EXPECT_LT(r.tail, 1e-12) << dt;
    EXPECT_FALSE(r.truncated) << dt;
    EXPECT_LT(r.l1, 1e-12) << dt;  // the model against itself
    ASSERT_EQ(r.e_out.size(), r.t.size());
    EXPECT_NEAR(r.e_out[20], (r.c_out[20] - 0.5) / r.outlet.area, 1e-15);
    EXPECT_TRUE(rtd_warnings(r, c).empty());
  }
}

// The model on the channel's boundary conditions (inlet held at the feed, no dispersive flux
// at x = L): as the channel grows longer (Pe_L up) its ends matter less and its moments tend
// to those of the semi-infinite medium, V/Q and 2 K L / U^3; at the benchmark's length they
// are well apart.
TEST(RtdModel, ClosedOutletModelTendsToTheOpenOneAtLargePecletLength) {
  std::vector<double> mean_dev, var_dev;
  for (const double length : {100.0, 1000.0, 10000.0}) {
    Case c = pulse_case();
    c.geometry.length = length;
    const analysis::TaylorAris m = analysis::taylor_aris(c);
    c.species.feed.t0 = 0.0;
    c.species.feed.width = 0.05 * m.space_time;
    const double t_end = m.space_time + 12.0 * std::sqrt(m.residence.variance());
    std::vector<double> t;
    for (int i = 0; i <= 4000; ++i) t.push_back(t_end * i / 4000.0);
    const auto g = analysis::closed_outlet_excess(c, m, t);
    const analysis::CurveMoments cm = analysis::curve_moments(t, g);
    const FeedMoments fm = feed_moments(c.species);
    mean_dev.push_back((cm.mean - fm.mean) / m.space_time - 1.0);
    var_dev.push_back((cm.variance - fm.variance) / m.residence.variance() - 1.0);
    std::printf(
        "L = %g: Pe_L = %.4g, closed model t_m / tau - 1 = %+.4f, s^2 / (2KL/U^3) - 1 = "
        "%+.4f, recovery %.5f\n",
        length, m.peclet_length, mean_dev.back(), var_dev.back(), cm.area / fm.amount);
  }
  EXPECT_LT(mean_dev[0], -0.03) << "at Pe_L = 15.6 the channel's ends shorten the mean";
  EXPECT_LT(std::abs(mean_dev[1]), 0.5 * std::abs(mean_dev[0]));
  EXPECT_LT(std::abs(mean_dev[2]), 0.5 * std::abs(mean_dev[1]));
  EXPECT_LT(std::abs(mean_dev[2]), 0.01);
  EXPECT_LT(std::abs(var_dev[2]), 0.5 * std::abs(var_dev[0]));
}

// A run stopped at 1.2 s, before the tail: flagged, the moments too small, and the warning
// says what to do.
TEST(RtdMoments, TruncatedOutletIsFlagged) {
  const Case c = pulse_case();
  const analysis::Rtd r = analysis::residence_time_distribution(model_outlet(c, 0.005, 1.2), c);
  EXPECT_TRUE(r.truncated);
  EXPECT_GT(r.tail, 0.01);
  EXPECT_LT(r.mean_residence_time, 0.75 * 0.95);
  EXPECT_LT(r.recovery, 0.95);
  const auto warnings = rtd_warnings(r, c);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_THAT(warnings[0], HasSubstr("time.t_end"));
}

// A reacting tracer, initial contents other than the base, no diffusion: each is named with
// the key to change; without D there is no model, and the outputs say so (null, empty).
TEST(RtdMoments, WarningsSayWhatToChange) {
  const auto rows = model_outlet(pulse_case(), 0.005, 8.0);
  Case c = pulse_case();
  c.species.k = 1.462;
  c.species.c_init = 2.0;
  const auto warnings = rtd_warnings(analysis::residence_time_distribution(rows, c), c);
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_THAT(warnings[0], HasSubstr("sets species.k = 0"));
  EXPECT_THAT(warnings[1], HasSubstr("sets species.c_init = species.feed.base"));
  Case still = pulse_case();
  still.species.D = 0.0;
  const analysis::Rtd r = analysis::residence_time_distribution(rows, still);
  EXPECT_FALSE(r.has_model);
  EXPECT_TRUE(std::isnan(r.l1));
  EXPECT_NEAR(r.mean_residence_time, 0.75, 1e-6);  // the moments need no model
  EXPECT_THAT(rtd_warnings(r, still).back(), HasSubstr("species.D = 0"));
  EXPECT_THAT(analysis::rtd_json(r, still), HasSubstr("\"L1\": null"));
  EXPECT_THAT(analysis::rtd_csv(r), HasSubstr("\n8,0.5,0,,,\n"));
}

// The L1 distance of normalised curves: 2 less the overlap for curves that hardly overlap
// (the run's response 4 s after the model's, where the model has fallen to ~1e-7 of its peak).
TEST(RtdMoments, DisjointShapesAreAtDistanceTwo) {
  const Case c = pulse_case();
  const InverseGaussian e = analysis::taylor_aris(c).residence;
  std::vector<OutletRow> late;
  for (int i = 0; i <= 2400; ++i) {
    const double t = 0.005 * i;
    const double v = 0.5 + analysis::model_outlet_excess(c.species, e, t - 4.0);
    late.push_back({t, v, v});
  }
  const analysis::Rtd r = analysis::residence_time_distribution(late, c);
  EXPECT_NEAR(r.l1, 2.0, 1e-6);
  EXPECT_LE(r.l1, 2.0);
  EXPECT_NEAR(r.mean_residence_time, 4.75, 1e-4);
}

TEST(RtdMoments, BadInputNamesWhatToFix) {
  Case c = pulse_case();
  const auto rows = model_outlet(c, 0.005, 8.0);
  auto source_of = [](const std::vector<OutletRow>& rs, const Case& cs) {
    try {
      analysis::residence_time_distribution(rs, cs);
    } catch (const analysis::RtdInputError& e) {
      return std::make_pair(e.source(), std::string(e.what()));
    }
    ADD_FAILURE() << "no RtdInputError";
    return std::make_pair(analysis::RtdInputError::Source::feed, std::string());
  };
  using Source = analysis::RtdInputError::Source;
  Case step = c;
  step.species.feed.shape = FeedShape::step;
  EXPECT_EQ(source_of(rows, step).first, Source::feed);
  EXPECT_THAT(source_of(rows, step).second, HasSubstr("\"pulse\" or \"table\""));
  Case open_table = c;
  open_table.species.feed.shape = FeedShape::table;
  open_table.species.feed.table = {{0.0, 0.5}, {0.1, 2.5}};  // ends above the base
  EXPECT_EQ(source_of(rows, open_table).first, Source::feed);
  const auto few = std::vector<OutletRow>(rows.begin(), rows.begin() + 2);
  EXPECT_EQ(source_of(few, c).first, Source::outlet);
  EXPECT_THAT(source_of(few, c).second, HasSubstr("at least 3"));
  std::vector<OutletRow> flat_rows;
  for (int i = 0; i < 10; ++i) flat_rows.push_back({0.1 * i, 0.5, 0.5});
  EXPECT_EQ(source_of(flat_rows, c).first, Source::outlet);
  EXPECT_THAT(source_of(flat_rows, c).second, HasSubstr("zero area"));
}

// A table describing the pulse's rectangle with edges eps = 1e-6 s wide: each ramp of height
// dC contributes dC times the mean of F over the ramp, F(t - t_edge - eps/2) to O(eps^2), so
// the table's model differs from the pulse formula by at most dC (eps/2) max E, asserted.
TEST(RtdModel, TableFeedConvolutionMatchesThePulseFormula) {
  const Case pulse = pulse_case();
  Case table = pulse;
  const double t0 = 0.1, w = 0.05, eps = 1e-6;
  table.species.feed.shape = FeedShape::table;
  table.species.feed.table = {{0.0, 0.5},          {t0 - eps, 0.5}, {t0, 2.5},
                              {t0 + w - eps, 2.5}, {t0 + w, 0.5},   {3.0, 0.5}};
  const InverseGaussian e = analysis::taylor_aris(pulse).residence;
  double max_e = 0.0;
  for (int i = 1; i < 2000; ++i) max_e = std::max(max_e, analysis::pdf(e, 1e-3 * i));
  const double tol = 2.0 * (eps / 2.0) * max_e;
  for (int i = 0; i <= 300; ++i) {
    const double t = 0.01 * i;
    EXPECT_NEAR(analysis::model_outlet_excess(table.species, e, t),
                analysis::model_outlet_excess(pulse.species, e, t), tol)
        << t;
  }
}

// A triangular table feed (slopes over 0.2 s, Simpson's rule on F per segment): the model's
// outlet has the feed's moments plus E's (means and variances of a convolution add), to the
// trapezoid tolerance of the sampling, (dt / sigma)^2 / 12.
TEST(RtdModel, TableFeedModelAddsTheMoments) {
  Case c = pulse_case();
  c.species.feed.shape = FeedShape::table;
  c.species.feed.table = {{0.0, 0.5}, {0.1, 0.5}, {0.3, 2.5}, {0.4, 1.5}, {0.5, 0.5}};
  const FeedMoments feed = feed_moments(c.species);
  const InverseGaussian e = analysis::taylor_aris(c).residence;
  const double dt = 0.005, tol = dt * dt / (12.0 * e.variance());
  std::vector<double> t, g;
  for (int i = 0; i <= 1800; ++i) {
    t.push_back(dt * i);
    g.push_back(analysis::model_outlet_excess(c.species, e, t.back()));
  }
  const analysis::CurveMoments m = analysis::curve_moments(t, g);
  EXPECT_NEAR(m.area, feed.amount, tol * feed.amount);
  EXPECT_NEAR(m.mean, feed.mean + e.mean, tol * e.mean);
  EXPECT_NEAR(m.variance, feed.variance + e.variance(), tol * e.variance());
}

// ---- against the transient reference ----

// The run's own series as the reference: the same moments, and the shapes at distance 0.
TEST(RtdAgainst, IdenticalSeriesAreAtDistanceZero) {
  const Case c = pulse_case();
  const auto rows = model_outlet(c, 0.005, 8.0);
  const analysis::Rtd r = analysis::residence_time_distribution(rows, c);
  const analysis::RtdAgainst a = analysis::against_reference(r, c, rows, c);
  EXPECT_EQ(a.l1, 0.0);
  EXPECT_EQ(a.mean_residence_time, r.mean_residence_time);
  EXPECT_EQ(a.variance, r.variance);
  EXPECT_EQ(a.mean_over_reference_minus_1, 0.0);
  EXPECT_EQ(a.variance_over_reference_minus_1, 0.0);
  EXPECT_EQ(a.recovery, r.recovery);
  ASSERT_EQ(a.c_ref.size(), r.t.size());
  for (std::size_t i = 0; i < r.t.size(); ++i) EXPECT_EQ(a.c_ref[i], r.c_out[i]);
  EXPECT_TRUE(a.case_differences.empty());
}

// A reference whose response arrives delta = 0.05 s later, for the same feed, sampled five
// times as often (interpolated onto the run's samples): its mean residence time is the run's
// plus delta, so the run's relative difference is t_m / (t_m + delta) - 1 = -6.25 %; the
// variance is the same; L1 is the distance of the two shapes, int |E(t) - E(t - delta)| dt,
// computed here on a fine grid. Tolerances: the trapezoid rule's (dt / sigma)^2 / 12 at the
// run's dt = 0.005 s (3e-5), and the linear interpolation's dt^2 max|E''| / 8 for L1.
TEST(RtdAgainst, ShiftedReferenceGivesTheShiftAsMeanDifference) {
  const Case c = pulse_case();
  const double delta = 0.05;
  const analysis::Rtd r = analysis::residence_time_distribution(model_outlet(c, 0.005, 8.0), c);
  const InverseGaussian e = analysis::taylor_aris(c).residence;
  std::vector<OutletRow> late;
  std::vector<double> t, g_run, g_ref;
  for (int i = 0; i <= 9000; ++i) {
    const double ti = 0.001 * i;
    const double v = 0.5 + analysis::model_outlet_excess(c.species, e, ti - delta);
    late.push_back({ti, v, v});
    if (ti > 8.0) continue;
    t.push_back(ti);
    g_run.push_back(analysis::model_outlet_excess(c.species, e, ti));
    g_ref.push_back(v - 0.5);
  }
  const analysis::RtdAgainst a = analysis::against_reference(r, c, late, c);
  EXPECT_NEAR(a.mean_residence_time, 0.75 + delta, 1e-4);
  EXPECT_NEAR(a.variance, r.variance, 1e-4 * r.variance);
  EXPECT_NEAR(a.mean_over_reference_minus_1, 0.75 / (0.75 + delta) - 1.0, 2e-4);
  EXPECT_NEAR(a.variance_over_reference_minus_1, 0.0, 2e-4);
  const double area = analysis::curve_moments(t, g_run).area;
  for (double& v : g_run) v /= area;
  for (double& v : g_ref) v /= area;
  const double l1 = analysis::l1_distance(t, g_run, g_ref);
  EXPECT_GT(l1, 0.1);
  EXPECT_NEAR(a.l1, l1, 2e-3 * l1);
}

// The reference must cover the run's first and last sample; otherwise the error says which
// times each covers and what to do.
TEST(RtdAgainst, ReferenceMustCoverTheRun) {
  const Case c = pulse_case();
  const auto rows = model_outlet(c, 0.005, 8.0);
  const analysis::Rtd r = analysis::residence_time_distribution(rows, c);
  auto message = [&](const std::vector<OutletRow>& ref) {
    try {
      analysis::against_reference(r, c, ref, c);
    } catch (const analysis::RtdInputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::vector<OutletRow> short_ref(rows.begin(), rows.begin() + 1201);  // to 6 s
  EXPECT_THAT(message(short_ref), HasSubstr("cover t = 0 to 6 s, not the run's t = 0 to 8 s"));
  EXPECT_THAT(message(short_ref), HasSubstr("time.t_end >= 8"));
  const std::vector<OutletRow> late_start(rows.begin() + 1, rows.end());
  EXPECT_THAT(message(late_start), HasSubstr("cover t = 0.005 to 8 s"));
  EXPECT_THAT(message({rows[0], rows[1]}), HasSubstr("at least 3"));
}

// A reference solved for another case is named key by key.
TEST(RtdAgainst, OtherCaseIsNamed) {
  const Case c = pulse_case();
  const auto rows = model_outlet(c, 0.005, 8.0);
  const analysis::Rtd r = analysis::residence_time_distribution(rows, c);
  Case other = c;
  other.species.D = 1000.0;
  other.species.feed.width = 0.1;
  const analysis::RtdAgainst a = analysis::against_reference(r, c, rows, other);
  ASSERT_EQ(a.case_differences.size(), 2u);
  EXPECT_EQ(a.case_differences[0], "species.D: run 10, reference 1000");
  EXPECT_EQ(a.case_differences[1], "species.feed.width: run 0.05, reference 0.1");
  // Its own feed corrects its moments: width 0.1 s has mean 0.05 s later than 0.05 s's.
  EXPECT_NEAR(a.mean_residence_time, r.mean_residence_time - 0.025, 1e-12);
  EXPECT_THAT(analysis::rtd_markdown(r, c, &a), HasSubstr("another case: species.D"));
}

// ---- the command ----

constexpr const char* kCaseText = R"(name = "rtd_cli"
flow = "prescribed"
[particles]
dx = 0.5
[species]
D = 10.0
k = 0.0
c_in = 2.5
c_init = 0.5
[species.feed]
shape = "pulse"
t0 = 0.1
width = 0.05
base = 0.5
[time]
t_end = 8.0
stop_when_steady = false
[output]
outlet_interval = 0.005
)";

// A run directory as `adrsph run` leaves it: case.toml, run.json and the outlet of a run
// that follows the model for `c` (the case as run, overrides applied).
void make_run_dir(const fs::path& dir, const Case& c, const std::string& overrides = "[]") {
  fs::create_directories(dir);
  test::write_file(dir / "case.toml", kCaseText);
  test::write_file(dir / "run.json", "{\"status\": \"ok\", \"overrides\": " + overrides + "}\n");
  write_outlet_csv(dir / "outlet.csv", model_outlet(c, 0.005, 8.0));
}

Case cli_case() {
  Case c = pulse_case();
  c.name = "rtd_cli";
  return c;
}

nlohmann::json read_json(const fs::path& file) {
  return nlohmann::json::parse(test::read_file(file));
}

TEST(RtdCommand, WritesTheMeanResidenceTime) {
  test::TempDir dir;
  make_run_dir(dir / "run", cli_case());
  const auto r = test::run_adrsph("rtd run --no-plot", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("# Residence-time distribution: rtd_cli"));
  EXPECT_THAT(r.out, HasSubstr("| mean residence time t_m [s] | 0.75 | V/Q = L/U = 0.75 |"));
  EXPECT_THAT(r.out, HasSubstr("only indicative"));  // tau D / R^2 = 0.3
  const auto j = read_json(dir / "run" / "rtd.json");
  EXPECT_NEAR(j["mean_residence_time"].get<double>(), 0.75, 1e-4);
  EXPECT_NEAR(j["space_time"].get<double>(), 0.75, 1e-12);
  EXPECT_NEAR(j["Pe"].get<double>(), 1000.0, 1e-9);
  EXPECT_EQ(j["case"], "rtd_cli");
  EXPECT_EQ(j["feed"]["shape"], "pulse");
  EXPECT_DOUBLE_EQ(j["feed"]["t0"].get<double>(), 0.1);
  EXPECT_FALSE(j["truncated"].get<bool>());
  EXPECT_LT(j["L1"].get<double>(), 1e-6);
  const std::string csv = test::read_file(dir / "run" / "rtd.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "t_s,C_out,E_per_s,C_model,C_model_closed,C_reference");
  EXPECT_EQ(csv.substr(csv.size() - 2), ",\n");  // no reference: C_reference empty
  EXPECT_TRUE(j["reference"].is_null());
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1602);
  EXPECT_EQ(test::read_file(dir / "run" / "rtd.md").find("# Residence-time distribution"), 0u);
  EXPECT_FALSE(fs::exists(dir / "run" / "rtd.png"));
}

// The case is the one run.json's overrides made: the pulse at 0.3 s, not case.toml's 0.1 s.
// Ignoring them would put the mean residence time 0.2 s late.
TEST(RtdCommand, AppliesTheRunsOverridesAndWritesToOut) {
  test::TempDir dir;
  Case c = cli_case();
  c.species.feed.t0 = 0.3;
  make_run_dir(dir / "run", c, "[\"species.feed.t0=0.3\"]");
  const auto r = test::run_adrsph("rtd run --no-plot --out report", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NEAR(read_json(dir / "report" / "rtd.json")["mean_residence_time"].get<double>(), 0.75,
              1e-4);
  EXPECT_TRUE(fs::exists(dir / "report" / "rtd.csv"));
  EXPECT_TRUE(fs::exists(dir / "report" / "rtd.md"));
  EXPECT_FALSE(fs::exists(dir / "run" / "rtd.json"));
}

// A network with an inert tracer T beside a reacting A: --species T takes T's feed, D and
// outlet series (outlet_T.csv) and writes rtd_T.*; the first species has no pulse, and the
// error says which species there are.
constexpr const char* kNetworkCaseText = R"(name = "rtd_net"
flow = "prescribed"
[particles]
dx = 0.5
[[species]]
name = "A"
D = 10.0
c_in = 1.0
[[species]]
name = "T"
D = 10.0
c_in = 2.5
c_init = 0.5
[species.feed]
shape = "pulse"
t0 = 0.1
width = 0.05
base = 0.5
[[reaction]]
law = "first_order"
k = 1.0
reactants = ["A"]
[time]
t_end = 8.0
stop_when_steady = false
[output]
outlet_interval = 0.005
)";

TEST(RtdCommand, SpeciesOfANetwork) {
  test::TempDir dir;
  const fs::path run = dir / "run";
  fs::create_directories(run);
  test::write_file(run / "case.toml", kNetworkCaseText);
  test::write_file(run / "run.json", "{\"status\": \"ok\", \"overrides\": []}\n");
  write_outlet_csv(run / "outlet_T.csv", model_outlet(cli_case(), 0.005, 8.0));
  write_outlet_csv(run / "outlet.csv", {{0.0, 1.0, 1.0}, {0.1, 1.0, 1.0}, {0.2, 1.0, 1.0}});

  auto r = test::run_adrsph("rtd run --species T --no-plot", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("# Residence-time distribution: rtd_net (species T)"));
  EXPECT_THAT(r.out, HasSubstr("| mean residence time t_m [s] | 0.75 | V/Q = L/U = 0.75 |"));
  EXPECT_THAT(r.out, Not(HasSubstr("the tracer reacts")));  // the reaction is A's
  const auto j = read_json(run / "rtd_T.json");
  EXPECT_NEAR(j["mean_residence_time"].get<double>(), 0.75, 1e-4);
  EXPECT_LT(j["L1"].get<double>(), 1e-6);
  EXPECT_TRUE(fs::exists(run / "rtd_T.csv"));
  EXPECT_TRUE(fs::exists(run / "rtd_T.md"));
  EXPECT_FALSE(fs::exists(run / "rtd.json"));

  r = test::run_adrsph("rtd run --no-plot", dir.path());  // A: a constant feed
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("\"pulse\" or \"table\""));
  EXPECT_THAT(r.err, HasSubstr("--species NAME takes another of \"A\", \"T\""));
  r = test::run_adrsph("rtd run --species Q --no-plot", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--species Q"));
  EXPECT_THAT(r.err, HasSubstr("has no species of that name (it has \"A\", \"T\")"));
  EXPECT_FALSE(fs::exists(run / "rtd.json"));
}

TEST(RtdCommand, MissingRunDirOrCaseExits2) {
  test::TempDir dir;
  const auto r = test::run_adrsph("rtd nowhere --no-plot", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("nowhere"));
  EXPECT_THAT(r.err, HasSubstr("adrsph run"));
  make_run_dir(dir / "run", cli_case());
  fs::remove(dir / "run" / "case.toml");
  const auto no_case = test::run_adrsph("rtd run --no-plot", dir.path());
  EXPECT_EQ(no_case.exit_code, 2);
  EXPECT_THAT(no_case.err, HasSubstr("case.toml: not found"));
}

// Without a readable run.json the overrides are unknown: refused, not guessed.
TEST(RtdCommand, MissingOrMalformedRunJsonExits2) {
  test::TempDir dir;
  make_run_dir(dir / "run", cli_case());
  test::write_file(dir / "run" / "run.json", "{\"overrides\": [");
  auto r = test::run_adrsph("rtd run --no-plot", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("run.json: not valid JSON"));
  fs::remove(dir / "run" / "run.json");
  r = test::run_adrsph("rtd run --no-plot", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("run.json: not found"));
  EXPECT_FALSE(fs::exists(dir / "run" / "rtd.json"));
}

TEST(RtdCommand, MissingOutletCsvExits2) {
  test::TempDir dir;
  make_run_dir(dir / "run", cli_case());
  fs::remove(dir / "run" / "outlet.csv");
  const auto r = test::run_adrsph("rtd run --no-plot", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("outlet.csv"));
  EXPECT_THAT(r.err, HasSubstr("output.outlet_interval > 0"));
  EXPECT_FALSE(fs::exists(dir / "run" / "rtd.json"));
}

TEST(RtdCommand, StepFeedExits2) {
  test::TempDir dir;
  make_run_dir(dir / "run", cli_case(), "[\"species.feed.shape=\\\"step\\\"\"]");
  const auto r = test::run_adrsph("rtd run --no-plot", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("case.toml"));
  EXPECT_THAT(r.err, HasSubstr("species.feed.shape = \"pulse\" or \"table\""));
  EXPECT_FALSE(fs::exists(dir / "run" / "rtd.json"));
}

TEST(RtdCommand, TooFewSamplesOrNoTracerExit2) {
  test::TempDir dir;
  make_run_dir(dir / "run", cli_case());
  write_outlet_csv(dir / "run" / "outlet.csv", {{0.0, 0.5, 0.5}, {0.1, 0.6, 0.6}});
  auto r = test::run_adrsph("rtd run --no-plot", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("outlet.csv"));
  EXPECT_THAT(r.err, HasSubstr("at least 3"));
  write_outlet_csv(dir / "run" / "outlet.csv", {{0.0, 0.5, 0.5}, {0.1, 0.5, 0.5}, {0.2, 0.5, 0.5}});
  r = test::run_adrsph("rtd run --no-plot", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("outlet.csv"));
  EXPECT_THAT(r.err, HasSubstr("zero area"));
  EXPECT_THAT(r.err, HasSubstr("time.t_end"));
  EXPECT_FALSE(fs::exists(dir / "run" / "rtd.json"));
}

// --against: the reference (here the run's own outlet, with its case.toml and run.json as
// `adrsph reference --transient` writes them) in rtd.md, rtd.json and the C_reference column.
TEST(RtdCommand, AgainstAddsTheReference) {
  test::TempDir dir;
  make_run_dir(dir / "run", cli_case());
  make_run_dir(dir / "ref", cli_case());
  const auto r = test::run_adrsph("rtd run --no-plot --against ref", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("## Against the transient reference"));
  EXPECT_THAT(r.out, HasSubstr("| mean residence time t_m [s] | 0.75 | 0.75 | +0.00% |"));
  const auto j = read_json(dir / "run" / "rtd.json");
  EXPECT_EQ(j["reference"]["L1"].get<double>(), 0.0);
  EXPECT_NEAR(j["reference"]["mean_residence_time"].get<double>(), 0.75, 1e-4);
  EXPECT_EQ(j["reference"]["samples"].get<int>(), 1601);
  EXPECT_TRUE(j["reference"]["case_differences"].empty());
  const std::string csv = test::read_file(dir / "run" / "rtd.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "t_s,C_out,E_per_s,C_model,C_model_closed,C_reference");
  // Each row ends with C_reference = C_out (the same series): at t = 8, the base 0.5.
  EXPECT_EQ(csv.substr(csv.rfind('\n', csv.size() - 2) + 1, 5), "8,0.5");
  EXPECT_EQ(csv.substr(csv.size() - 5), ",0.5\n");
}

TEST(RtdCommand, AgainstMissingOrShortReferenceExits2) {
  test::TempDir dir;
  make_run_dir(dir / "run", cli_case());
  fs::create_directories(dir / "ref");
  auto r = test::run_adrsph("rtd run --no-plot --against ref", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("ref/outlet.csv: not found"));
  EXPECT_THAT(r.err, HasSubstr("--transient"));
  // A bare outlet series (no case.toml: the run's case) that ends at 4 s.
  write_outlet_csv(dir / "ref" / "outlet.csv", model_outlet(cli_case(), 0.005, 4.0));
  r = test::run_adrsph("rtd run --no-plot --against ref", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("ref/outlet.csv"));
  EXPECT_THAT(r.err, HasSubstr("cover t = 0 to 4 s, not the run's t = 0 to 8 s"));
  EXPECT_FALSE(fs::exists(dir / "run" / "rtd.json"));
}

TEST(RtdCommand, HelpSaysWhatItNeeds) {
  test::TempDir dir;
  const auto r = test::run_adrsph("rtd --help", dir.path());
  EXPECT_EQ(r.exit_code, 0);
  for (const char* s : {"outlet_interval", "\"pulse\"", "outlet.csv", "run.json", "--out",
                        "--no-plot", "--against", "Exit codes"})
    EXPECT_THAT(r.out, HasSubstr(s));
}

}  // namespace
}  // namespace adrsph
