// The [[reaction]] tables: exact single-reaction updates against a fine numerical integration
// of their rate laws, the zones of k(x, y), the case-file tables, the steady test's bound,
// and the SPH particles of a prescribed flow without diffusion, each an exact batch reactor.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/steady_state.hpp"
#include "integrator/sph_solver.hpp"
#include "species/reaction_kinetics.hpp"
#include "sph_test_cases.hpp"

namespace adrsph {
namespace {

using ::testing::HasSubstr;

double rate(const Reaction& r, double k, double c) {
  switch (r.law) {
    case RateLaw::first_order:
      return k * c;
    case RateLaw::nth_order:
      return c > 0.0 ? k * std::pow(c, r.order) : 0.0;
    case RateLaw::michaelis_menten:
      return k * c / (r.km + c);
    case RateLaw::bimolecular:
      break;  // two species: test_reaction_network.cpp
  }
  return 0.0;
}

// dC/dt = -R(C) by classical Runge-Kutta with 20000 steps (error ~1e-16 relative here).
double integrate(const Reaction& r, double k, double c0, double t) {
  const int n = 20000;
  const double h = t / n;
  double c = c0;
  for (int i = 0; i < n; ++i) {
    const double k1 = -rate(r, k, c), k2 = -rate(r, k, c + 0.5 * h * k1);
    const double k3 = -rate(r, k, c + 0.5 * h * k2), k4 = -rate(r, k, c + h * k3);
    c = std::max(0.0, c + h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4));
  }
  return c;
}

TEST(ReactionKinetics, ExactUpdatesMatchTheRateLaws) {
  const std::vector<Reaction> laws = {Reaction::of(RateLaw::first_order, 1.5, 1.0, 0.0, {}),
                                      Reaction::of(RateLaw::nth_order, 0.7, 2.0, 0.0, {}),
                                      Reaction::of(RateLaw::nth_order, 0.4, 3.0, 0.0, {}),
                                      Reaction::of(RateLaw::nth_order, 0.9, 0.5, 0.0, {}),
                                      Reaction::of(RateLaw::michaelis_menten, 1.2, 1.0, 0.5, {}),
                                      Reaction::of(RateLaw::michaelis_menten, 1.2, 1.0, 5.0, {})};
  for (const Reaction& r : laws)
    for (const double t : {0.01, 0.3, 1.0}) {
      const double exact = react_exact(r, r.k, 2.0, t), ode = integrate(r, r.k, 2.0, t);
      EXPECT_NEAR(exact, ode, 1e-10 * 2.0) << to_string(r.law) << " n " << r.order << " t " << t;
      // Exact means composable: two half steps give the whole step.
      const double halves = react_exact(r, r.k, react_exact(r, r.k, 2.0, t / 2), t / 2);
      EXPECT_NEAR(halves, exact, 1e-13) << to_string(r.law);
    }
  // Below first order the species is used up at finite time and stays at 0; zero order too.
  const Reaction half = Reaction::of(RateLaw::nth_order, 1.0, 0.5, 0.0, {});
  EXPECT_EQ(react_exact(half, 1.0, 1.0, 2.0 + 1e-9), 0.0);  // C^(1/2) = 1 - t/2
  EXPECT_NEAR(react_exact(half, 1.0, 1.0, 1.0), 0.25, 1e-15);
  const Reaction zero_km = Reaction::of(RateLaw::michaelis_menten, 1.0, 1.0, 0.0, {});
  EXPECT_DOUBLE_EQ(react_exact(zero_km, 1.0, 2.0, 0.5), 1.5);
  EXPECT_EQ(react_exact(zero_km, 1.0, 2.0, 3.0), 0.0);
  EXPECT_EQ(react_exact(laws[1], 0.7, 0.0, 1.0), 0.0);
}

TEST(ReactionKinetics, ZonesScaleTheRateConstant) {
  Reaction r = Reaction::of(RateLaw::first_order, 1.0, 1.0, 0.0,
                            {{10, 20, -5, 0, 3.0}, {15, 30, -5, 5, 0.5}});
  EXPECT_EQ(zone_factor(r, 12.0, -1.0), 3.0);
  EXPECT_EQ(zone_factor(r, 16.0, -1.0), 3.0);  // the first zone that holds the point
  EXPECT_EQ(zone_factor(r, 16.0, 1.0), 0.5);
  EXPECT_EQ(zone_factor(r, 20.0, -1.0), 0.5);  // x1 is outside the first zone
  EXPECT_EQ(zone_factor(r, 5.0, 0.0), 1.0);
}

TEST(ReactionKinetics, CaseFileReadsReactionTables) {
  const Case c = load_case_text(
      "name = \"r\"\n[[reaction]]\nlaw = \"nth_order\"\nk = 0.5\norder = 2.0\n"
      "[[reaction]]\nlaw = \"michaelis_menten\"\nk = 1.0\nkm = 0.3\n"
      "zones = [[20.0, 40.0, -5.0, 5.0, 10.0]]\n",
      "r.toml");
  ASSERT_EQ(c.reactions.size(), 2u);
  EXPECT_EQ(c.reactions[0].law, RateLaw::nth_order);
  EXPECT_EQ(c.reactions[0].order, 2.0);
  EXPECT_EQ(c.reactions[1].km, 0.3);
  ASSERT_EQ(c.reactions[1].zones.size(), 1u);
  EXPECT_EQ(c.reactions[1].zones[0].factor, 10.0);
  EXPECT_EQ(c.species.k, 0.0) << "with [[reaction]] tables, species.k defaults to 0";
  const Case both = load_case_text(
      "name = \"r\"\n[species]\nk = 1.0\n[[reaction]]\nlaw = \"nth_order\"\nk = 0.5\n", "r.toml");
  EXPECT_EQ(both.species.k, 1.0) << "an explicit species.k stays";
  const Case none = load_case_text("name = \"r\"\n", "r.toml");
  EXPECT_EQ(none.species.k, 1.462) << "no [[reaction]]: the paper's first-order default";
  const Case set =
      load_case_text("name = \"r\"\n", "r.toml", {"reaction=[{law = \"first_order\", k = 2.0}]"});
  ASSERT_EQ(set.reactions.size(), 1u);
  EXPECT_EQ(set.species.k, 0.0);
}

struct BadReaction {
  std::string text, key, expected;
};

class ReactionErrors : public ::testing::TestWithParam<BadReaction> {};

TEST_P(ReactionErrors, NameTheKey) {
  const BadReaction& b = GetParam();
  try {
    load_case_text("name = \"r\"\n" + b.text, "r.toml");
    FAIL() << "accepted: " << b.text;
  } catch (const CaseError& e) {
    EXPECT_EQ(e.key(), b.key) << e.what();
    EXPECT_THAT(e.what(), HasSubstr(b.expected));
    EXPECT_EQ(e.file(), "r.toml");
  }
}

INSTANTIATE_TEST_SUITE_P(
    Tables, ReactionErrors,
    ::testing::Values(
        BadReaction{"[[reaction]]\nlaw = \"second\"\n", "reaction[0].law", "\"nth_order\""},
        BadReaction{"[[reaction]]\nkk = 1.0\n", "reaction[0].kk", "law, k, order, km"},
        BadReaction{"[[reaction]]\nk = -1.0\n", "reaction[0].k", "[0, 1e+20]"},
        BadReaction{"[[reaction]]\nlaw = \"nth_order\"\norder = 6.0\n", "reaction[0].order",
                    "[0, 5]"},
        BadReaction{"[[reaction]]\nlaw = \"michaelis_menten\"\nkm = -1\n", "reaction[0].km",
                    "[0, 1e+20]"},
        BadReaction{"[[reaction]]\nk = 1\n[[reaction]]\nzones = [[5, 1, 0, 1, 2]]\n",
                    "reaction[1].zones[0]", "x0 < x1"},
        BadReaction{"[[reaction]]\nzones = [[0, 1, 0, 1]]\n", "reaction[0].zones[0]",
                    "a zone [x0, x1, y0, y1, factor]"},
        BadReaction{"[[reaction]]\nzones = [[0, 1, 0, 1, -2]]\n", "reaction[0].zones[0][4]",
                    "[0, 1e+20]"},
        BadReaction{"reaction = 3\n", "reaction", "an array of tables"}));

// With a first-order [[reaction]] in place of species.k, the steady test's earliest stop is
// the closed form's (the batch tables reproduce c exp(-k t)).
TEST(ReactionKinetics, SteadyBoundMatchesTheFirstOrderClosedForm) {
  Case closed;
  Case table = closed;
  table.species.k = 0.0;
  table.reactions = {Reaction::of(RateLaw::first_order, closed.species.k, 1.0, 0.0, {})};
  const double t_closed = steady_criterion(closed).t_min, t_table = steady_criterion(table).t_min;
  EXPECT_GT(t_closed, 1.0);
  EXPECT_NEAR(t_table, t_closed, 0.0101);
  for (const double t : {0.5, 2.0, 4.0})
    // To 0.5%: the tables interpolate linearly between points 2.3% apart in tau.
    EXPECT_NEAR(cold_start_transient(table, t), cold_start_transient(closed, t),
                5e-3 * cold_start_transient(closed, t))
        << t;
}

// Prescribed flow without diffusion: every fluid particle is a batch reactor that has reacted
// for min(t, x / u(y)) (the initial fluid since t = 0, the fluid fed since it crossed x = 0),
// so its C is the batch solution at that age, up to the step in which it crossed x = 0 (and a
// zone edge): at most ~2 dt of reaction.
TEST(ReactionKinetics, PrescribedFlowParticlesAreBatchReactors) {
  for (const Reaction& r :
       {Reaction::of(RateLaw::nth_order, 0.8, 2.0, 0.0, {}),
        Reaction::of(RateLaw::michaelis_menten, 3.0, 1.0, 0.4, {}),
        Reaction::of(RateLaw::first_order, 2.0, 1.0, 0.0, {{5, 10, -5, 5, 4.0}})}) {
    Case c = testing::short_channel(Scheme::modern, Flow::prescribed);
    c.species.D = 0.0;
    c.species.k = 0.0;
    c.species.c_in = c.species.c_init = 2.0;
    c.reactions = {r};
    SphSolver solver(c);
    const double dt = solver.dt_limits().chosen;
    while (solver.time() < 0.15 - 1e-12) ASSERT_TRUE(solver.step(dt));
    const double t = solver.time();
    const ParticleStore& s = solver.particles();
    const ChannelScene scene(c);
    double worst = 0.0;
    int checked = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (s.kind[i] != kFluidByte) continue;
      const double u = scene.inflow_velocity(s.y[i]);
      const double age = std::min(t, s.x[i] / u);
      // Time spent in each zone along the path x(t') = x - u (t - t') over the age.
      double k_time = r.k * age;
      for (const auto& z : r.zones) {
        if (s.y[i] < z.y0 || s.y[i] >= z.y1) continue;
        const double in = std::max(0.0, std::min(s.x[i], z.x1) - std::max(s.x[i] - u * age, z.x0));
        k_time += (z.factor - 1.0) * r.k * in / u;
      }
      const double expected = age > 0.0 ? react_exact(r, k_time / age, 2.0, age) : 2.0;
      const double step_reaction = 2.0 * dt * r.k * 4.0 * 2.0;  // 2 steps at the largest rate
      worst = std::max(worst, std::fabs(s.c[i] - expected) / step_reaction);
      ++checked;
    }
    std::printf("%s: worst |C - batch| / (2 steps of reaction) = %.3f over %d particles\n",
                to_string(r.law), worst, checked);
    EXPECT_GT(checked, 700);  // 20 mm x 10 mm of fluid at dx = 0.5: 800 particles
    EXPECT_LT(worst, 1.0);
  }
}

}  // namespace
}  // namespace adrsph
