// The transient mode of the network reference (reference_network_transient.hpp): one species
// against the single-species transient solver, the approach to the steady network, each
// species' balance of a reacting pulse, second order in time, and `adrsph reference
// --transient` on a network (small grids: fast).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <utility>
#include <vector>

#include "adrsph/reference_network_transient.hpp"
#include "io_test_util.hpp"

namespace adrsph::reference {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

Case::Species species(const char* name, double D, double c_in, double c_init) {
  Case::Species s;
  s.name = name;
  s.D = D;
  s.k = 0.0;
  s.c_in = c_in;
  s.c_init = c_init;
  return s;
}

Reaction bimolecular(double k, int a, int b, int product) {
  Reaction r;
  r.law = RateLaw::bimolecular;
  r.k = k;
  r.reactants = {a, b};
  r.products = {product};
  return r;
}

// A + B -> C on the benchmark channel at D = 100 (Pe = 100): A pulsed (height 1 over
// [0.0123, 0.0494)), B fed steadily at 1 into a channel full of it, C made in the channel.
Case network_pulse_case(double k) {
  Case c;
  c.species = species("A", 100.0, 1.0, 0.0);
  c.species.feed.shape = FeedShape::pulse;
  c.species.feed.t0 = 0.0123;
  c.species.feed.width = 0.0371;
  c.more_species = {species("B", 100.0, 1.0, 1.0), species("C", 100.0, 0.0, 0.0)};
  c.reactions = {bimolecular(k, 0, 1, 2)};
  c.time.t_end = 3.0;
  c.output.outlet_interval = 0.004;
  return c;
}

double max_distance(const std::vector<OutletRow>& a, const std::vector<OutletRow>& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
    d = std::max(d, std::abs(a[i].c_flow - b[i].c_flow));
  return d;
}

double peak(const std::vector<OutletRow>& a) {
  double p = 0.0;
  for (const OutletRow& r : a) p = std::max(p, std::abs(r.c_flow));
  return p;
}

// A one-species network is the single-species transient problem: a Michaelis-Menten pulse
// (nonlinear: the single-species solver iterates it about a slope bound, the network by
// Newton) gives the same outlet series to the iterations' tolerance (both 1e-12 per step;
// asserted 1e-8 of the peak) and the same amount reacted.
TEST(ReferenceNetworkTransient, OneSpeciesIsTheSingleSpeciesSolve) {
  Case c;
  c.species = species("A", 100.0, 1.0, 0.0);
  c.species.feed.shape = FeedShape::pulse;
  c.species.feed.t0 = 0.0123;
  c.species.feed.width = 0.0371;
  c.reactions = {Reaction::of(RateLaw::michaelis_menten, 1.0, 1.0, 0.5, {})};
  c.time.t_end = 2.0;
  c.output.outlet_interval = 0.004;
  TransientOptions opt;
  opt.dt = 0.004;
  opt.tolerance = 1e-12;
  const TransientSolution one = solve_transient(transient_problem_from_case(c), 80, 8, opt);
  const NetworkTransientSolution net =
      solve_network_transient(network_transient_problem_from_case(c), 80, 8, opt);
  ASSERT_EQ(net.outlet.size(), 1u);
  ASSERT_EQ(net.outlet[0].size(), one.outlet.size());
  EXPECT_TRUE(net.report.started_at_rest);
  EXPECT_TRUE(net.report.converged);
  const double d = max_distance(one.outlet, net.outlet[0]), p = peak(one.outlet);
  std::printf("outlet peak %.6f, largest distance %.2e\n", p, d);
  EXPECT_GT(p, 0.01);
  EXPECT_LT(d, 1e-8 * p);
  EXPECT_NEAR(net.balance[0].reacted, one.balance.reacted, 1e-8 * one.balance.inflow);
  EXPECT_GT(one.balance.reacted, 0.05 * one.balance.inflow);
}

// Constant feeds into a channel free of every species (not at rest: the implicit-Euler start)
// tend to the steady network on the same grid: BDF2's fixed point is the steady scheme (N1).
// A + B -> C with k = 2: by t = 8 s the channel has been flushed ten times (measured
// distance 1e-12 of the feed); asserted 1e-8.
TEST(ReferenceNetworkTransient, ConstantFeedsTendToTheSteadyNetwork) {
  Case c;
  c.species = species("A", 100.0, 2.0, 0.0);
  c.more_species = {species("B", 100.0, 1.5, 0.0), species("C", 100.0, 0.0, 0.0)};
  c.reactions = {bimolecular(2.0, 0, 1, 2)};
  c.time.t_end = 8.0;
  c.output.outlet_interval = 0.5;
  TransientOptions opt;
  opt.dt = 0.01;
  const NetworkTransientSolution tr =
      solve_network_transient(network_transient_problem_from_case(c), 80, 8, opt);
  EXPECT_FALSE(tr.report.started_at_rest);
  EXPECT_TRUE(tr.report.converged);
  const NetworkSolution steady = solve_network_steady(network_problem_from_case(c), 80, 8);
  ASSERT_TRUE(steady.report.converged);
  double worst = 0.0;
  for (std::size_t s = 0; s < 3; ++s)
    for (std::size_t i = 0; i < steady.c[s].size(); ++i)
      worst = std::max(worst, std::abs(tr.final.c[s][i] - steady.c[s][i]) / 2.0);
  std::printf("largest distance to the steady network at t = 8 s: %.2e of the feed\n", worst);
  EXPECT_LT(worst, 1e-8);
  // The reaction acts: C is made (its steady outlet is well above 0).
  EXPECT_GT(tr.outlet[2].back().c_flow, 0.1);
}

// A reacting pulse (A + B -> C, k = 2, Pe = 100) from rest (nothing reacts before A arrives:
// BDF2 from the first step), run until A and C have left. For every species what entered is
// what left, what was consumed and what is held, to the iteration's tolerance (measured
// 5e-13 of A's inflow); one reaction, so A and B are consumed alike and C made as much.
TEST(ReferenceNetworkTransient, ReactingPulseBalancesEverySpecies) {
  const Case c = network_pulse_case(2.0);
  TransientOptions opt;
  opt.dt = 0.004;
  const NetworkTransientSolution tr =
      solve_network_transient(network_transient_problem_from_case(c), 80, 8, opt);
  ASSERT_TRUE(tr.report.started_at_rest);
  EXPECT_TRUE(tr.report.converged);
  ASSERT_EQ(tr.balance.size(), 3u);
  const double fed = tr.balance[0].inflow;
  for (std::size_t s = 0; s < 3; ++s) {
    const TransientBalance& b = tr.balance[s];
    const double closure = b.inflow - b.outflow - b.reacted - (b.held_final - b.held_initial);
    std::printf("%s: in %.6f, out %.6f, consumed %.6f, held %.6f -> %.6f: closure %.1e\n",
                c.species_at(static_cast<int>(s)).name.c_str(), b.inflow, b.outflow, b.reacted,
                b.held_initial, b.held_final, closure / fed);
    EXPECT_LT(std::abs(closure), 1e-9 * fed) << "species " << s;
  }
  EXPECT_GT(tr.balance[0].reacted, 0.1 * fed);  // a real share of the pulse reacts
  EXPECT_NEAR(tr.balance[1].reacted, tr.balance[0].reacted, 1e-12 * fed);
  EXPECT_NEAR(tr.balance[2].reacted, -tr.balance[0].reacted, 1e-12 * fed);
  // A and C have left; B is back to its feed.
  EXPECT_LT(tr.outlet[0].back().c_flow, 1e-6 * peak(tr.outlet[0]));
  EXPECT_LT(tr.outlet[2].back().c_flow, 1e-6 * peak(tr.outlet[2]));
  EXPECT_NEAR(tr.outlet[1].back().c_flow, 1.0, 1e-6);
}

// Second order in time for the coupled nonlinear system: the product's outlet series at
// dt = 4, 2, 1 ms (upwind advection, so that only the time integration and the kinetics
// are in play) converge with ratio |r_dt - r_dt/2| / |r_dt/2 - r_dt/4| near 4.
TEST(ReferenceNetworkTransient, ProductSeriesIsSecondOrderInTime) {
  Case c = network_pulse_case(2.0);
  c.species.feed.width = 0.2;  // a pulse the steps resolve (as the single-species test)
  c.species.feed.t0 = 0.0;
  c.time.t_end = 2.0;
  c.output.outlet_interval = 0.04;
  const NetworkTransientProblem p = network_transient_problem_from_case(c);
  std::vector<std::vector<OutletRow>> series;
  for (const double dt : {0.004, 0.002, 0.001}) {
    TransientOptions opt;
    opt.dt = dt;
    opt.limiter = Limiter::upwind;
    opt.tolerance = 1e-13;
    series.push_back(solve_network_transient(p, 80, 8, opt).outlet[2]);
  }
  const double coarse = max_distance(series[0], series[1]),
               fine = max_distance(series[1], series[2]);
  std::printf("C outlet: max %.3e -> %.3e (ratio %.2f)\n", coarse, fine, coarse / fine);
  EXPECT_GT(peak(series[2]), 0.01);
  EXPECT_NEAR(coarse / fine, 4.0, 0.3);
}

// A reaction stiff against the step (k C_B dt = 7: the coupling between A and B outweighs
// the storage term) is more than the species blocks settle: those steps finish on the
// coupled matrix, converged, and the balances still close once the pulse has left (BDF2's
// storage telescopes to the change held plus half the last step's change).
TEST(ReferenceNetworkTransient, StiffReactionFinishesOnTheCoupledMatrix) {
  Case c = network_pulse_case(2000.0);
  c.time.t_end = 3.0;
  TransientOptions opt;
  opt.dt = 0.004;
  // The rate's slope k C_B = 2000 1/s turns the iteration's remainder into a balance error
  // (3e-7 of the feed at the default 1e-10): the closure is asserted at a tighter tolerance.
  opt.tolerance = 1e-13;
  const NetworkTransientSolution tr =
      solve_network_transient(network_transient_problem_from_case(c), 80, 8, opt);
  std::printf("%ld of %ld steps coupled, %d factorisations, %.1f iterations per step\n",
              tr.coupled_steps, tr.report.steps, tr.factorisations,
              static_cast<double>(tr.report.corrections) / static_cast<double>(tr.report.steps));
  EXPECT_TRUE(tr.report.converged);
  EXPECT_GT(tr.coupled_steps, 0);
  const double fed = tr.balance[0].inflow;
  EXPECT_GT(tr.balance[0].reacted, 0.99 * fed);  // nearly all of A reacts
  for (const TransientBalance& b : tr.balance)
    EXPECT_LT(std::abs(b.inflow - b.outflow - b.reacted - (b.held_final - b.held_initial)),
              1e-8 * fed);
}

TEST(ReferenceNetworkTransient, BadInputIsNamed) {
  NetworkTransientProblem p = network_transient_problem_from_case(network_pulse_case(1.0));
  p.feeds.pop_back();
  EXPECT_THROW(
      {
        try {
          solve_network_transient(p, 20, 2);
        } catch (const std::invalid_argument& e) {
          EXPECT_THAT(e.what(), HasSubstr("one feed per species"));
          throw;
        }
      },
      std::invalid_argument);
}

// ---- the command ----

using test::case_arg;

// cases/network_pulse_pe1000.toml on a coarse grid: one outlet series per species under the
// SPH run's names, run.json with each species' balance; `adrsph rtd` reads the reference as a
// run, its species A by --species (against itself: distance 0).
TEST(ReferenceNetworkTransientCli, WritesEverySpeciesSeries) {
  test::TempDir dir;
  const auto r = test::run_adrsph("reference " + case_arg("network_pulse_pe1000.toml") +
                                      " --transient --nx 40 --ny 4 --dt 0.005 --set "
                                      "time.t_end=3 --out ref",
                                  dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("BDF2 from rest"));
  for (const char* f : {"outlet.csv", "outlet_B.csv", "outlet_C.csv"})
    EXPECT_EQ(read_outlet_csv(dir / "ref" / f).size(), 301u) << f;  // t = 0, 0.01, ..., 3
  const auto j = nlohmann::json::parse(test::read_file(dir / "ref" / "run.json"));
  EXPECT_EQ(j["status"], "ok");
  EXPECT_EQ(j["network"], true);
  EXPECT_EQ(j["species"], nlohmann::json::array({"A", "B", "C"}));
  const double consumed = j["balance"]["A"]["reacted"].get<double>();
  EXPECT_GT(consumed, 0.0);
  EXPECT_NEAR(j["balance"]["C"]["reacted"].get<double>(), -consumed, 1e-12);

  const auto rtd = test::run_adrsph("rtd ref --species A --against ref --no-plot", dir.path());
  ASSERT_EQ(rtd.exit_code, 0) << rtd.err;
  const auto report = nlohmann::json::parse(test::read_file(dir / "ref" / "rtd.json"));
  EXPECT_LT(report["recovery"].get<double>(), 0.9);  // A reacts on its way
  EXPECT_NEAR(report["reference"]["L1"].get<double>(), 0.0, 1e-12);

  // `adrsph compare` against a transient reference: every species' outlet series.
  const auto cmp = test::run_adrsph("compare ref ref --out cmp.md", dir.path());
  ASSERT_EQ(cmp.exit_code, 0) << cmp.err;
  for (const char* row : {"| A | 301 |", "| B | 301 |", "| C | 301 |"})
    EXPECT_THAT(cmp.out, HasSubstr(row));
  EXPECT_THAT(cmp.out, HasSubstr("| 0.00% | 0.00% |"));
  EXPECT_TRUE(fs::exists(dir / "cmp.md"));
}

}  // namespace
}  // namespace adrsph::reference
