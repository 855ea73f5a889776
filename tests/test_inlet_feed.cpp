// The inlet feed in time ([species.feed]): its values and moments, the buffer that carries
// it in a run, and the outlet series (outlet.csv) that measures what leaves.
#include <gtest/gtest.h>

#include <cmath>

#include "adrsph/simulation.hpp"
#include "integrator/sph_solver.hpp"
#include "io_test_util.hpp"
#include "species/feed_integral.hpp"
#include "species/inlet_feed.hpp"
#include "sph_test_cases.hpp"

namespace adrsph {
namespace {

Case::Species pulse(double t0, double width) {
  Case::Species s;
  s.c_in = 2.0;
  s.feed.shape = FeedShape::pulse;
  s.feed.t0 = t0;
  s.feed.width = width;
  s.feed.base = 0.5;
  return s;
}

TEST(InletFeed, ValuesOfEachShape) {
  Case::Species s;
  s.c_in = 2.0;
  EXPECT_EQ(inlet_concentration(s, 7.0), 2.0);
  EXPECT_FALSE(feed_varies(s));

  s.feed.shape = FeedShape::step;
  s.feed.t0 = 1.0;
  s.feed.base = 0.25;
  EXPECT_EQ(inlet_concentration(s, 0.999), 0.25);
  EXPECT_EQ(inlet_concentration(s, 1.0), 2.0);
  EXPECT_TRUE(feed_varies(s));

  const auto p = pulse(1.0, 0.5);
  EXPECT_EQ(inlet_concentration(p, 0.99), 0.5);
  EXPECT_EQ(inlet_concentration(p, 1.0), 2.0);
  EXPECT_EQ(inlet_concentration(p, 1.49), 2.0);
  EXPECT_EQ(inlet_concentration(p, 1.5), 0.5);
  EXPECT_EQ(feed_max(p), 2.0);

  Case::Species t;
  t.feed.shape = FeedShape::table;
  t.feed.table = {{1.0, 0.0}, {2.0, 4.0}, {4.0, 1.0}};
  EXPECT_EQ(inlet_concentration(t, 0.0), 0.0);  // held before the first point
  EXPECT_DOUBLE_EQ(inlet_concentration(t, 1.5), 2.0);
  EXPECT_DOUBLE_EQ(inlet_concentration(t, 3.0), 2.5);
  EXPECT_EQ(inlet_concentration(t, 9.0), 1.0);  // held after the last
  EXPECT_EQ(feed_max(t), 4.0);
}

TEST(InletFeed, MomentsOfPulseAndTable) {
  const auto m = feed_moments(pulse(1.0, 0.5));
  EXPECT_DOUBLE_EQ(m.amount, 1.5 * 0.5);
  EXPECT_DOUBLE_EQ(m.mean, 1.25);
  EXPECT_DOUBLE_EQ(m.variance, 0.25 / 12.0);

  // A triangle 0 -> 1 -> 0 over [1, 3]: area 1, mean 2, variance 1/6.
  Case::Species t;
  t.feed.shape = FeedShape::table;
  t.feed.table = {{1.0, 0.0}, {2.0, 1.0}, {3.0, 0.0}};
  const auto tm = feed_moments(t);
  EXPECT_NEAR(tm.amount, 1.0, 1e-14);
  EXPECT_NEAR(tm.mean, 2.0, 1e-14);
  EXPECT_NEAR(tm.variance, 1.0 / 6.0, 1e-13);

  Case::Species step;
  step.feed.shape = FeedShape::step;
  EXPECT_TRUE(std::isinf(feed_moments(step).amount));
}

TEST(InletFeed, CaseFileReadsTheFeedTable) {
  const Case c = load_case_text(
      "name = \"x\"\n[species]\nc_in = 1.0\n[species.feed]\nshape = \"table\"\n"
      "table = [[0.0, 0.0], [0.1, 1.0], [0.2, 0.0]]\n[time]\nstop_when_steady = false\n"
      "[output]\noutlet_interval = 0.01\n",
      "feed.toml");
  EXPECT_EQ(c.species.feed.shape, FeedShape::table);
  ASSERT_EQ(c.species.feed.table.size(), 3u);
  EXPECT_EQ(c.species.feed.table[1][0], 0.1);
  EXPECT_EQ(c.species.feed.table[1][1], 1.0);
  EXPECT_EQ(c.output.outlet_interval, 0.01);
}

// The inflow buffer carries the feed's mean over each step, so that what it holds over the run
// is the feed's amount whatever the step; nothing of a pulse reaches the fluid before the
// pulse starts.
TEST(InletFeed, InflowBufferCarriesThePulse) {
  Case c = testing::short_channel(Scheme::modern, Flow::prescribed);
  c.species.c_init = 0.0;
  c.species.c_in = 1.0;
  c.species.feed.shape = FeedShape::pulse;
  c.species.feed.t0 = 0.0203;  // edges inside steps (dt = 0.625 ms)
  c.species.feed.width = 0.0301;
  SphSolver solver(c);
  const double dt = solver.dt_limits().chosen;
  int inside = 0, outside = 0, partial = 0;
  double held = 0.0, held_mid_step = 0.0;  // int C_buffer dt, and what mid-step values give
  while (solver.time() < 0.08) {
    const double t0 = solver.time();
    ASSERT_TRUE(solver.step(dt));
    const double mean = feed_integral(c.species, t0, t0 + dt) / dt;
    const ParticleStore& s = solver.particles();
    double fluid_max = 0.0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (s.kind[i] == kInletByte) {
        ASSERT_EQ(s.c[i], mean);
      }
      if (s.kind[i] == kFluidByte) fluid_max = std::max(fluid_max, s.c[i]);
    }
    if (solver.time() < c.species.feed.t0) {
      EXPECT_EQ(fluid_max, 0.0);
    }
    held += mean * dt;
    held_mid_step += inlet_concentration(c.species, t0 + 0.5 * dt) * dt;
    (mean > 1.0 - 1e-9 ? inside : mean < 1e-9 ? outside : partial) += 1;
  }
  std::printf(
      "pulse amount 0.0301 mol/m^3 s: buffer holds %.9f (mid-step values: %.9f), dt = %.3g\n", held,
      held_mid_step, dt);
  EXPECT_GT(inside, 10);
  EXPECT_GT(outside, 10);
  EXPECT_GE(partial, 1) << "a pulse edge inside a step, where the mean is a fraction";
  EXPECT_NEAR(held, c.species.c_in * c.species.feed.width, 1e-12);
  EXPECT_GT(solver.species_inventory(), 0.0);
}

// What the outlet series says leaves the channel (flow rate times the flow-weighted mean C at
// x = L, integrated over the samples) against what the particles that crossed x = L carried
// (the species ledger): the two measures of one outflow. A conserved pulse, prescribed flow.
TEST(InletFeed, OutletSeriesMeasuresTheOutflow) {
  Case c = testing::short_channel(Scheme::modern, Flow::prescribed);
  c.species.c_init = 0.0;
  c.species.c_in = 1.0;
  c.species.k = 0.0;
  c.species.feed.shape = FeedShape::pulse;
  c.species.feed.width = 0.05;
  SphSolver solver(c);
  const double dt = solver.dt_limits().chosen, every = 0.005;
  // Flow rate of the profile u = u_max (1 - (y/R)^2): Q = (4/3) u_max R per unit depth.
  const double q = 4.0 / 3.0 * c.u_max() * c.geometry.half_width;
  const int n_points = 40;
  double t_prev = 0.0, c_prev = 0.0, measured = 0.0, next = every;
  while (solver.time() < 1.5) {
    ASSERT_TRUE(solver.step(dt));
    if (solver.time() < next - 1e-12) continue;
    next += every;
    const OutletRow row =
        solver.sampler().outlet_means(c.geometry.length, c.geometry.half_width, n_points);
    measured += 0.5 * (row.c_flow + c_prev) * (solver.time() - t_prev) * q;
    t_prev = solver.time();
    c_prev = row.c_flow;
  }
  const double crossed = solver.species_ledger().outflow;
  std::printf("outflow: outlet series %.5f, particles crossing x = L %.5f (ratio %.4f)\n", measured,
              crossed, measured / crossed);
  EXPECT_GT(crossed, 0.9 * q * c.species.feed.width) << "most of the pulse has left";
  // Measured 0.9988: the samples are 0.005 s apart (trapezoid rule) and the kernel sum
  // smooths C over 3h at x = L.
  EXPECT_NEAR(measured / crossed, 1.0, 0.005);
}

}  // namespace
}  // namespace adrsph
