// The transient reference (docs/reference.md, "Transient mode"): the feed's window integrals,
// the approach to the steady solution, the tracer balance of a pulse, second order in time,
// and `adrsph reference --transient` (small grids: fast).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "adrsph/reference_transient.hpp"
#include "io_test_util.hpp"
#include "reference_test_util.hpp"
#include "species/feed_integral.hpp"

namespace adrsph::reference {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

// A conserved tracer pulse of height 1 on base 0 over [t0, t0 + width) into a channel free of
// it, at diffusivity D, on the benchmark channel (U = 133.3 mm/s, V/Q = 0.75 s).
Case pulse_case(double D, double t0, double width) {
  Case c;
  c.species.D = D;
  c.species.k = 0.0;
  c.species.c_in = 1.0;
  c.species.c_init = 0.0;
  c.species.feed.shape = FeedShape::pulse;
  c.species.feed.t0 = t0;
  c.species.feed.width = width;
  c.species.feed.base = 0.0;
  return c;
}

// int_a^b of every feed shape against its closed form, including windows that straddle a
// pulse's edges, a step and a table's points and run past its ends.
TEST(ReferenceTransient, FeedIntegralIsExact) {
  Case::Species s;
  s.c_in = 2.0;
  EXPECT_DOUBLE_EQ(feed_integral(s, 1.0, 1.5), 1.0);
  s.feed.base = 0.5;
  s.feed.t0 = 1.0;
  s.feed.shape = FeedShape::step;
  EXPECT_DOUBLE_EQ(feed_integral(s, 0.5, 1.25), 0.5 * 0.5 + 2.0 * 0.25);
  s.feed.shape = FeedShape::pulse;
  s.feed.width = 0.1;
  EXPECT_DOUBLE_EQ(feed_integral(s, 0.95, 1.05), 0.5 * 0.1 + 1.5 * 0.05);
  EXPECT_DOUBLE_EQ(feed_integral(s, 0.0, 3.0), 0.5 * 3.0 + 1.5 * 0.1);
  EXPECT_NEAR(feed_integral(s, 1.02, 1.03), 2.0 * 0.01, 1e-15);
  EXPECT_EQ(feed_integral(s, 1.0, 1.0), 0.0);
  s.feed.shape = FeedShape::table;
  s.feed.table = {{1.0, 0.0}, {2.0, 4.0}, {4.0, 1.0}};
  EXPECT_DOUBLE_EQ(feed_integral(s, 0.0, 1.0), 0.0);
  EXPECT_DOUBLE_EQ(feed_integral(s, 1.5, 3.0), 0.5 * (2.0 + 4.0) * 0.5 + 0.5 * (4.0 + 2.5));
  EXPECT_DOUBLE_EQ(feed_integral(s, 3.0, 6.0), 0.5 * (2.5 + 1.0) + 2.0 * 1.0);
}

// The step taken divides the sample interval, so that every sample falls on a step.
TEST(ReferenceTransient, StepDividesTheSampleInterval) {
  EXPECT_DOUBLE_EQ(step_dividing(0.001, 0.01), 0.001);
  EXPECT_DOUBLE_EQ(step_dividing(0.003, 0.01), 0.0025);
  EXPECT_DOUBLE_EQ(step_dividing(0.05, 0.01), 0.01);
  Case c = pulse_case(10.0, 0.0, 0.05);
  c.output.outlet_interval = 0.01;
  EXPECT_DOUBLE_EQ(default_transient_dt(c), 0.001);  // min(width, interval) / 10
  c.species.feed.width = 0.004;
  EXPECT_DOUBLE_EQ(default_transient_dt(c), 0.0004);
}

// A constant feed of 2 into a channel at 0 (not at rest: the implicit-Euler start) tends to
// the steady solution on the same grid: BDF2's fixed point is the steady scheme, so the
// distance is what the transient has left, below e^{-k t} of the start with k = 1.462 1/s and
// the channel flushed many times over by t = 8 s (measured: 1e-11). Stations and the whole
// field within 1e-8 relative.
TEST(ReferenceTransient, ConstantFeedTendsToTheSteadySolution) {
  Case c;
  c.species.D = 10.0;
  c.species.c_init = 0.0;
  c.time.t_end = 8.0;
  c.output.outlet_interval = 0.5;
  TransientProblem p = transient_problem_from_case(c);
  TransientOptions opt;
  opt.dt = 0.01;
  const TransientSolution tr = solve_transient(p, 80, 8, opt);
  EXPECT_FALSE(tr.report.started_at_rest);
  EXPECT_TRUE(tr.report.converged);
  EXPECT_DOUBLE_EQ(tr.t_reached, 8.0);
  ASSERT_EQ(tr.outlet.size(), 17u);
  const Solution steady = solve_steady(p.space, 80, 8);
  const StationTable a = station_table(tr.final, p.space), b = station_table(steady, p.space);
  for (std::size_t m = 0; m < a.c_mean.size(); ++m)
    EXPECT_NEAR(a.c_mean[m], b.c_mean[m], 1e-8 * b.c_mean[m]) << "station " << m;
  double worst = 0.0;
  for (std::size_t i = 0; i < steady.c.size(); ++i)
    worst = std::max(worst, std::abs(tr.final.c[i] - steady.c[i]) / steady.c[i]);
  std::printf("largest relative distance to the steady field at t = 8 s: %.2e\n", worst);
  EXPECT_LT(worst, 1e-8);
  // The outlet series ends at the steady outlet's flow-weighted mean.
  EXPECT_NEAR(tr.outlet.back().c_flow, outlet_row(steady, p.space, 8.0).c_flow, 1e-8);
}

// A conserved pulse, its edges off the step grid, through the parabolic channel at Pe = 10
// (40x4), sampled every step, long enough to leave (6 s: 1e-11 of it is still held).
// (1) What left plus what is held is what entered through x = 0, advection plus the inlet
//     face's diffusion: BDF2 from rest telescopes exactly, to rounding (1e-12 of the amount).
// (2) With a linear scheme (upwind) the discrete system is linear time-invariant with steady
//     gain 1 (k = 0: C = 1 is its steady state for an inlet at 1), so what leaves is
//     Q int C_in dt exactly, however much tracer diffuses in and back out through the inlet:
//     the feed windows inject the feed's exact amount.
// (3) With van Leer the limiter makes the response nonlinear and the inlet face's net
//     diffusive exchange need not vanish: within 2e-3 of the feed's amount (measured 8.6e-4
//     on this coarse grid; 1e-5 at Pe = 10 and 3e-4 at Pe = 1000 on 400x40).
TEST(ReferenceTransient, ConservedPulseLeavesWithTheInjectedAmount) {
  const double t0 = 0.0123, width = 0.0371;
  Case c = pulse_case(1000.0, t0, width);
  c.time.t_end = 6.0;
  c.output.outlet_interval = 0.004;
  const TransientProblem p = transient_problem_from_case(c);
  const double fed = width * (c.species.c_in - c.species.feed.base);
  for (const Limiter limiter : {Limiter::upwind, Limiter::van_leer}) {
    TransientOptions opt;
    opt.dt = 0.004;
    opt.limiter = limiter;
    const TransientSolution tr = solve_transient(p, 40, 4, opt);
    ASSERT_TRUE(tr.report.started_at_rest);
    const auto& rows = tr.outlet;
    double left = 0.0, peak = 0.0;  // int C_flow dt: Q C_flow is the outflow
    for (std::size_t i = 1; i < rows.size(); ++i) {
      left += 0.5 * (rows[i].t - rows[i - 1].t) * (rows[i].c_flow + rows[i - 1].c_flow);
      peak = std::max(peak, rows[i].c_flow);
    }
    ASSERT_LT(rows.back().c_flow, 1e-9 * peak) << "the pulse has not left";
    const TransientBalance& b = tr.balance;
    EXPECT_LT(b.held_final, 1e-9 * fed);
    EXPECT_NEAR(left + b.held_final, b.inflow, 1e-12 * fed) << to_string(limiter);
    EXPECT_NEAR(b.outflow + b.held_final, b.inflow, 1e-12 * fed) << to_string(limiter);
    if (limiter == Limiter::upwind)
      EXPECT_NEAR(left + b.held_final, fed, 1e-12 * fed);
    else
      EXPECT_NEAR(left + b.held_final, fed, 2e-3 * fed);
  }
}

// Second order in time: the outlet series of a pulse (width 0.2 s, Pe = 100, 80x8) at dt,
// dt/2, dt/4 (4, 2, 1 ms) converge with ratio |r_dt - r_dt/2| / |r_dt/2 - r_dt/4| near 4.
// With the linear scheme (upwind) the time integration alone: measured 3.96 (max norm) and
// 4.01 (L1 over the samples), asserted 4 +- 0.3. With van Leer the limiter's switches at
// the moving extrema make the temporal error less regular: measured L1 ratio 3.80 (4.06 a
// level coarser), asserted 4 +- 0.5; max-norm ratio 3.46 (4.20), asserted > 3.
TEST(ReferenceTransient, OutletResponseIsSecondOrderInTime) {
  Case c = pulse_case(100.0, 0.0, 0.2);
  c.time.t_end = 2.0;
  c.output.outlet_interval = 0.04;
  const TransientProblem p = transient_problem_from_case(c);
  for (const Limiter limiter : {Limiter::upwind, Limiter::van_leer}) {
    std::vector<std::vector<OutletRow>> series;
    for (const double dt : {0.004, 0.002, 0.001}) {
      TransientOptions opt;
      opt.dt = dt;
      opt.limiter = limiter;
      opt.tolerance = 1e-13;
      series.push_back(solve_transient(p, 80, 8, opt).outlet);
    }
    auto distances = [&](std::size_t a, std::size_t b) {
      double max = 0.0, l1 = 0.0;
      for (std::size_t i = 0; i < series[a].size(); ++i) {
        const double d = std::abs(series[a][i].c_flow - series[b][i].c_flow);
        max = std::max(max, d);
        l1 += d * c.output.outlet_interval;
      }
      return std::make_pair(max, l1);
    };
    const auto coarse = distances(0, 1), fine = distances(1, 2);
    const double max_ratio = coarse.first / fine.first, l1_ratio = coarse.second / fine.second;
    std::printf("%s: max %.3e -> %.3e (ratio %.2f); L1 %.3e -> %.3e (ratio %.2f)\n",
                to_string(limiter), coarse.first, fine.first, max_ratio, coarse.second, fine.second,
                l1_ratio);
    if (limiter == Limiter::upwind) {
      EXPECT_NEAR(max_ratio, 4.0, 0.3);
      EXPECT_NEAR(l1_ratio, 4.0, 0.3);
    } else {
      EXPECT_GT(max_ratio, 3.0);
      EXPECT_NEAR(l1_ratio, 4.0, 0.5);
    }
  }
}

// ---- [[reaction]] tables (reaction_terms.cpp, iterated within each step) ----

// The benchmark channel at Pe = 1000 (80x8) with nonlinear kinetics: Michaelis-Menten
// everywhere, second order, and a first-order table confined to a zone.
Case kinetics_case() {
  Case c;
  c.species.D = 100.0;
  c.species.k = 0.0;
  c.species.c_in = 2.0;
  c.species.c_init = 2.0;
  c.reactions = {Reaction::of(RateLaw::michaelis_menten, 1.0, 1.0, 0.5, {}),
                 Reaction::of(RateLaw::nth_order, 0.3, 2.0, 0.0, {}),
                 Reaction::of(RateLaw::first_order, 2.0, 1.0, 0.0,
                              {{20.0, 60.0, 4.0, 5.0, 1.0}, {0.0, 100.0, -5.0, 5.0, 0.0}})};
  return c;
}

// A constant feed into a channel full of it (not at rest: it reacts, so the implicit-Euler
// start) tends to the steady solution of the same kinetics on the same grid: BDF2's fixed
// point is the steady scheme, whatever slope bound the iteration uses (c_max = 2 here, the
// steady solve's c_in). Measured distance at t = 8 s: 3.3e-12; asserted 1e-8.
TEST(ReferenceTransientKinetics, ConstantFeedTendsToTheSteadySolution) {
  Case c = kinetics_case();
  c.time.t_end = 8.0;
  c.output.outlet_interval = 0.5;
  const TransientProblem p = transient_problem_from_case(c);
  EXPECT_EQ(p.space.c_max, 2.0);
  TransientOptions opt;
  opt.dt = 0.01;
  const TransientSolution tr = solve_transient(p, 80, 8, opt);
  EXPECT_FALSE(tr.report.started_at_rest);
  EXPECT_TRUE(tr.report.converged);
  const Solution steady = solve_steady(p.space, 80, 8);
  ASSERT_TRUE(steady.report.converged);
  double worst = 0.0;
  for (std::size_t i = 0; i < steady.c.size(); ++i)
    worst = std::max(worst, std::abs(tr.final.c[i] - steady.c[i]) / steady.c[i]);
  std::printf("largest relative distance to the steady field at t = 8 s: %.2e (outlet %.6f)\n",
              worst, outlet_row(steady, p.space, 8.0).c_flow);
  EXPECT_LT(worst, 1e-8);
  // The kinetics act: the outlet is well below the feed.
  EXPECT_LT(outlet_row(steady, p.space, 8.0).c_flow, 1.5);
}

// A pulse of a reacting species into a channel free of it (at rest: nothing reacts at C = 0,
// so BDF2 from the first step). What entered is what left, what reacted (the tables' rates
// summed over the cells, reaction_total) and what is held, to the iteration's tolerance.
// The reaction takes a real share of the pulse (measured: 70%, closure 5e-12 of the inflow).
TEST(ReferenceTransientKinetics, PulseBalanceIncludesWhatReacted) {
  Case c = kinetics_case();
  c.species.c_init = 0.0;
  c.species.feed.shape = FeedShape::pulse;
  c.species.feed.t0 = 0.0123;
  c.species.feed.width = 0.0371;
  c.species.feed.base = 0.0;
  c.time.t_end = 3.0;
  c.output.outlet_interval = 0.004;
  const TransientProblem p = transient_problem_from_case(c);
  TransientOptions opt;
  opt.dt = 0.004;
  const TransientSolution tr = solve_transient(p, 80, 8, opt);
  ASSERT_TRUE(tr.report.started_at_rest);
  EXPECT_TRUE(tr.report.converged);
  const TransientBalance& b = tr.balance;
  const double closure = b.inflow - b.outflow - b.reacted - (b.held_final - b.held_initial);
  std::printf("in %.6f, out %.6f, reacted %.6f, held %.3e: closure %.2e of the inflow\n", b.inflow,
              b.outflow, b.reacted, b.held_final, closure / b.inflow);
  EXPECT_GT(b.reacted, 0.1 * b.inflow);
  EXPECT_LT(std::abs(closure), 1e-9 * b.inflow);
}

// A first-order [[reaction]] table is species.k by another name, in time as in the steady
// solve: the same outlet series.
TEST(ReferenceTransientKinetics, FirstOrderTableEqualsSpeciesK) {
  Case with_k = pulse_case(100.0, 0.0, 0.2);
  with_k.species.k = 1.462;
  with_k.time.t_end = 2.0;
  with_k.output.outlet_interval = 0.04;
  Case with_table = with_k;
  with_table.species.k = 0.0;
  with_table.reactions = {Reaction::of(RateLaw::first_order, 1.462, 1.0, 0.0, {})};
  TransientOptions opt;
  opt.dt = 0.004;
  const auto a = solve_transient(transient_problem_from_case(with_k), 80, 8, opt);
  const auto b = solve_transient(transient_problem_from_case(with_table), 80, 8, opt);
  ASSERT_EQ(a.outlet.size(), b.outlet.size());
  double diff = 0.0, peak = 0.0;
  for (std::size_t i = 0; i < a.outlet.size(); ++i) {
    diff = std::max(diff, std::abs(a.outlet[i].c_flow - b.outlet[i].c_flow));
    peak = std::max(peak, a.outlet[i].c_flow);
  }
  EXPECT_GT(peak, 0.01);
  EXPECT_LT(diff, 1e-9 * peak);
  EXPECT_NEAR(a.balance.reacted, b.balance.reacted, 1e-9 * a.balance.inflow);
}

// ---- the command ----

using test::case_arg;

// A short Pe = 10 pulse on a coarse grid: the directory holds outlet.csv, case.toml and
// run.json, and `adrsph rtd` reads it like a run's, --set values included.
TEST(ReferenceTransientCli, WritesARunDirectoryThatRtdReads) {
  test::TempDir dir;
  const auto r = test::run_adrsph("reference " + case_arg("rtd_pulse_pe10.toml") +
                                      " --transient --nx 40 --ny 4 --dt 0.005 --set "
                                      "species.feed.t0=0.1 --out ref",
                                  dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("BDF2 from rest"));
  const auto rows = read_outlet_csv(dir / "ref" / "outlet.csv");
  ASSERT_EQ(rows.size(), 401u);  // t = 0, 0.01, ..., 4
  EXPECT_DOUBLE_EQ(rows[1].t, 0.01);
  EXPECT_DOUBLE_EQ(rows.back().t, 4.0);
  EXPECT_EQ(test::read_file(dir / "ref" / "case.toml"),
            test::read_file(test::source_dir() / "cases" / "rtd_pulse_pe10.toml"));
  const auto j = nlohmann::json::parse(test::read_file(dir / "ref" / "run.json"));
  EXPECT_EQ(j["case"], "rtd_pulse_pe10");
  EXPECT_EQ(j["status"], "ok");
  EXPECT_EQ(j["transient"], true);
  EXPECT_EQ(j["overrides"], nlohmann::json::array({"species.feed.t0=0.1"}));
  EXPECT_EQ(j["grid"]["nx"], 40);
  EXPECT_EQ(j["grid"]["ny"], 4);
  EXPECT_DOUBLE_EQ(j["dt"].get<double>(), 0.005);
  EXPECT_TRUE(j["wall_seconds"].is_number());

  const auto rtd = test::run_adrsph("rtd ref --no-plot", dir.path());
  ASSERT_EQ(rtd.exit_code, 0) << rtd.err;
  const auto report = nlohmann::json::parse(test::read_file(dir / "ref" / "rtd.json"));
  EXPECT_DOUBLE_EQ(report["feed"]["t0"].get<double>(), 0.1);  // run.json's override
  // (The limiter's nonlinearity on this coarse grid: 1.1e-3 below 1; 1e-5 on 400x40.)
  EXPECT_NEAR(report["recovery"].get<double>(), 1.0, 5e-3);
  // At Pe = 10 the inlet held at the feed shortens the mean below V/Q (docs/rtd.md).
  EXPECT_LT(report["mean_residence_time"].get<double>(), 0.75);
  EXPECT_GT(report["mean_residence_time"].get<double>(), 0.6);
}

TEST(ReferenceTransientCli, NoOutletIntervalExits2) {
  test::TempDir dir;
  const auto r = test::run_adrsph("reference " + case_arg("rtd_pulse_pe10.toml") +
                                      " --transient --nx 40 --ny 4 --set "
                                      "output.outlet_interval=0 --out ref",
                                  dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("output.outlet_interval"));
  EXPECT_THAT(r.err, HasSubstr("rtd_pulse_pe10.toml"));
  EXPECT_FALSE(fs::exists(dir / "ref"));
}

TEST(ReferenceTransientCli, ConflictingOptionsExit2NamingThem) {
  test::TempDir dir;
  auto r = test::run_adrsph(
      "reference " + case_arg("rtd_pulse_pe10.toml") + " --transient --convergence", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--transient"));
  EXPECT_THAT(r.err, HasSubstr("--convergence"));
  r = test::run_adrsph("reference " + case_arg("lfr.toml") + " --dt 0.001", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--dt needs --transient"));
  r = test::run_adrsph("reference " + case_arg("rtd_pulse_pe10.toml") + " --transient --dt 0",
                       dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--dt"));
}

}  // namespace
}  // namespace adrsph::reference
