// Reaction networks in the SPH engine: several species ([[species]] tables) and reactions
// with reactants and products. The bimolecular update against a numerical integration, the
// case-file tables and their errors, element balances that the transport must keep exactly,
// the fused network pass against the one-species pass, and checkpoint/restart of a network.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <omp.h>

#include <array>
#include <cmath>

#include "adrsph/io/checkpoint_h5.hpp"
#include "adrsph/simulation.hpp"
#include "integrator/sph_solver.hpp"
#include "io_test_util.hpp"
#include "species/reaction_kinetics.hpp"
#include "sph_test_cases.hpp"

namespace adrsph {
namespace {

using ::testing::HasSubstr;

// dA/dt = dB/dt = -k A B by classical Runge-Kutta, 20000 steps.
double bimolecular_rk4(double k, double a, double b, double t) {
  const int n = 20000;
  const double h = t / n;
  auto f = [k](double x, double y) { return -k * x * y; };
  for (int i = 0; i < n; ++i) {
    const double k1 = f(a, b);
    const double k2 = f(a + 0.5 * h * k1, b + 0.5 * h * k1);
    const double k3 = f(a + 0.5 * h * k2, b + 0.5 * h * k2);
    const double k4 = f(a + h * k3, b + h * k3);
    const double d = h / 6.0 * (k1 + 2 * k2 + 2 * k3 + k4);
    a += d;
    b += d;
  }
  return a;
}

TEST(ReactionNetwork, BimolecularExtentMatchesTheRateLaw) {
  // Unequal, equal, nearly equal (Delta = 1e-12: the expm1 form must not cancel) and swapped.
  const std::array<std::array<double, 2>, 5> feeds = {
      {{2.0, 1.5}, {1.5, 2.0}, {1.0, 1.0}, {1.0, 1.0 + 1e-12}, {0.3, 3.0}}};
  for (const auto& [a0, b0] : feeds)
    for (const double t : {1e-4, 0.1, 2.0}) {
      const double k = 1.7;
      const double exact = a0 - bimolecular_extent(k, a0, b0, t);
      const double rk = bimolecular_rk4(k, a0, b0, t);
      EXPECT_NEAR(exact, rk, 1e-12 * a0) << "A0 = " << a0 << " B0 = " << b0 << " t = " << t;
    }
  EXPECT_EQ(bimolecular_extent(1.0, 0.0, 2.0, 1.0), 0.0);           // no A: nothing reacts
  EXPECT_NEAR(bimolecular_extent(1.0, 2.0, 1.0, 1e3), 1.0, 1e-12);  // B used up
}

constexpr const char* kNetworkCase = R"(
name = "net"
[[species]]
name = "A"
D = 10.0
c_in = 2.0
c_init = 2.0
[[species]]
name = "B"
D = 5.0
c_in = 1.5
c_init = 0.0
[species.feed]
shape = "step"
t0 = 0.5
base = 0.0
[[species]]
name = "P"
c_in = 0.0
c_init = 0.0
[[reaction]]
law = "bimolecular"
reactants = ["A", "B"]
products = ["P"]
k = 0.5
)";

TEST(ReactionNetwork, SpeciesTablesAndReactantsAreRead) {
  const Case c = load_case_text(kNetworkCase, "net.toml");
  ASSERT_EQ(c.species_count(), 3);
  EXPECT_EQ(c.species.name, "A");
  EXPECT_EQ(c.species.k, 0.0);  // reactions of a network are [[reaction]] tables
  EXPECT_EQ(c.species_at(1).name, "B");
  EXPECT_EQ(c.species_at(1).D, 5.0);
  EXPECT_EQ(c.species_at(1).feed.shape, FeedShape::step);  // [species.feed] of the last table
  EXPECT_EQ(c.species_at(1).feed.t0, 0.5);
  EXPECT_EQ(c.species_at(2).name, "P");
  EXPECT_EQ(c.species_at(2).D, 10.0);  // the default
  ASSERT_EQ(c.reactions.size(), 1u);
  EXPECT_EQ(c.reactions[0].law, RateLaw::bimolecular);
  EXPECT_EQ(c.reactions[0].reactants, (std::vector<int>{0, 1}));
  EXPECT_EQ(c.reactions[0].products, (std::vector<int>{2}));
  // A case of one species keeps its single [species] table, and its reactions take it.
  const Case one = load_case_text("[species]\nD = 1.0\n[[reaction]]\nk = 1.0\n", "one.toml");
  EXPECT_EQ(one.species_count(), 1);
  EXPECT_EQ(one.species.name, "C");
  EXPECT_EQ(one.reactions[0].reactants, (std::vector<int>{0}));
}

struct BadNetwork {
  std::string replace, with, key, says;
};

TEST(ReactionNetwork, BadTablesNameTheKey) {
  const std::vector<BadNetwork> bad = {
      {"reactants = [\"A\", \"B\"]", "reactants = [\"A\", \"Q\"]", "reaction[0].reactants[1]",
       "\"A\", \"B\", \"P\""},
      {"reactants = [\"A\", \"B\"]", "reactants = [\"A\"]", "reaction[0].reactants", "two species"},
      {"reactants = [\"A\", \"B\"]", "reactants = [\"A\", \"A\"]", "reaction[0].reactants",
       "two different"},
      {"reactants = [\"A\", \"B\"]", "reactants = []", "reaction[0].reactants", "got 0"},
      {"products = [\"P\"]", "products = [3]", "reaction[0].products[0]", "a string"},
      {"products = [\"P\"]", "products = [\"B\"]", "reaction[0].products[0]", "neither a reactant"},
      {"name = \"B\"", "name = \"A\"", "species[1].name", "no other species"},
      {"name = \"B\"", "name = \"B 2\"", "species[1].name", "letters, digits and _"},
      {"D = 5.0", "D = -5.0", "species[1].D", ">= 0"},
      {"D = 5.0", "k = 5.0", "species[1].k", "[[reaction]]"},
      {"law = \"bimolecular\"", "law = \"trimolecular\"", "reaction[0].law", "\"bimolecular\""},
  };
  for (const BadNetwork& b : bad) {
    std::string text = kNetworkCase;
    const auto at = text.find(b.replace);
    ASSERT_NE(at, std::string::npos) << b.replace;
    text.replace(at, b.replace.size(), b.with);
    try {
      load_case_text(text, "net.toml");
      ADD_FAILURE() << "accepted: " << b.with;
    } catch (const CaseError& e) {
      EXPECT_EQ(e.key(), b.key) << e.what();
      EXPECT_THAT(e.what(), HasSubstr(b.says));
    }
  }
  std::string five = kNetworkCase;
  for (const char* name : {"D1", "D2"})
    five += std::string("[[species]]\nname = \"") + name + "\"\n";
  EXPECT_THROW(load_case_text(five, "net.toml"), CaseError);
  EXPECT_THROW(load_case_text(std::string(kNetworkCase) + "[time]\nwarm_start = true\n", "n.toml"),
               CaseError);
}

// A + B -> P in a short channel; every species fed and started at uniform values.
Case network_channel(Scheme scheme, Flow flow, double d_b) {
  Case c = testing::short_channel(scheme, flow);
  c.species.name = "A";
  c.species.k = 0.0;
  c.species.c_in = c.species.c_init = 2.0;
  Case::Species b = c.species, p = c.species;
  b.name = "B";
  b.D = d_b;
  b.c_in = b.c_init = 1.5;
  p.name = "P";
  p.c_in = p.c_init = 0.0;
  c.more_species = {b, p};
  Reaction r;
  r.law = RateLaw::bimolecular;
  r.k = 2.0;
  r.reactants = {0, 1};
  r.products = {2};
  c.reactions = {r};
  validate_case(c);
  return c;
}

TEST(ReactionNetwork, TransportKeepsTheElementBalanceExactly) {
  // With D_A = D_P the sum A + P obeys the reaction-free transport of a field that starts and
  // enters at 2 everywhere: it must stay 2 (prescribed flow: div u = 0, no dilatation). With
  // D_B = D_A as well, B - A stays -0.5. The rates are single precision (6e-8 relative) and
  // A's and P's are rounded apart, so the sum holds to their rounding times the change
  // (measured 5e-13 in the optimised build, 1.4e-10 in the sanitizer build), not to double
  // round-off: the bound is 1e-8. A wrong D, a missing term or a reaction step that loses
  // moles moves the sum by the size of the reaction's change (P reaches 0.76).
  SphSolver s(network_channel(Scheme::modern, Flow::prescribed, 10.0));
  const double dt = s.dt_limits().chosen;
  for (int i = 0; i < 400; ++i) ASSERT_TRUE(s.step(dt)) << s.failure();
  const ParticleStore& p = s.particles();
  double sum_dev = 0.0, diff_dev = 0.0, reacted = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind[i] != kFluidByte) continue;
    sum_dev = std::max(sum_dev, std::fabs(p.c[i] + p.c_more[1][i] - 2.0));
    diff_dev = std::max(diff_dev, std::fabs(p.c_more[0][i] - p.c[i] + 0.5));
    reacted = std::max(reacted, p.c_more[1][i]);
  }
  std::printf("  t = %.3f s: max |A + P - 2| = %.2e, max |B - A + 0.5| = %.2e, max P = %.3f\n",
              s.time(), sum_dev, diff_dev, reacted);
  EXPECT_GT(reacted, 0.05);  // the reaction has run
  EXPECT_LT(sum_dev, 1e-8);
  EXPECT_LT(diff_dev, 1e-8);
}

// Every species keeps its own ledger: inflow - outflow + diffusive exchange with the buffers -
// net consumption = change of its inventory. A + B -> P with B diffusing at 3 mm^2/s (the
// others 10): the exchange is each species' own. The reaction's 1:1:1 stoichiometry shows in
// the consumptions: A's = B's = -P's. Prescribed flow, the fused pass and sub-cycled diffusion.
TEST(ReactionNetwork, EverySpeciesBalanceCloses) {
  for (const bool sub : {false, true}) {
    Case c = network_channel(Scheme::modern, Flow::prescribed, 3.0);
    if (sub) {
      for (Case::Species* sp : {&c.species, &c.more_species[0], &c.more_species[1]})
        sp->D *= 20.0;  // the diffusion limit below the flow step: sub-cycled
    }
    SphSolver s(c);
    EXPECT_EQ(s.dt_limits().diffusion_stages > 1, sub);
    s.track_species_balance(true);
    std::array<double, 3> start{};
    for (int e = 0; e < 3; ++e) start[e] = s.species_inventory(e);
    const double dt = s.dt_limits().chosen;
    for (int i = 0; i < 200; ++i) ASSERT_TRUE(s.step(dt)) << s.failure();
    for (int e = 0; e < 3; ++e) {
      const SpeciesLedger& l = s.species_ledger(e);
      const double change = s.species_inventory(e) - start[e];
      const double budget = l.inflow - l.outflow + l.buffer_exchange - l.reaction;
      const double scale = std::max({l.inflow, l.outflow, std::fabs(l.reaction)});
      std::printf("%s %s: in %.5g out %.5g exchange %.4g reaction %.5g | change %.6g budget %.6g\n",
                  sub ? "sub-cycled" : "fused", c.species_at(e).name.c_str(), l.inflow, l.outflow,
                  l.buffer_exchange, l.reaction, change, budget);
      if (e < 2) {
        EXPECT_GT(l.inflow, 0.0);
      } else {
        EXPECT_EQ(l.inflow, 0.0);  // P enters at 0
      }
      EXPECT_GT(l.outflow, 0.0);
      EXPECT_NE(l.buffer_exchange, 0.0);
      EXPECT_LT(std::fabs(change - budget), 1e-6 * scale) << c.species_at(e).name;
    }
    const double a = s.species_ledger(0).reaction;
    EXPECT_GT(a, 0.0);
    EXPECT_NEAR(s.species_ledger(1).reaction, a, 1e-9 * a);
    EXPECT_NEAR(s.species_ledger(2).reaction, -a, 1e-9 * a);
  }
}

TEST(ReactionNetwork, FusedPassEqualsTheOneSpeciesPass) {
  // In the weakly compressible flow A + P obeys the transport of a single reaction-free
  // species with C = 2 (the -C div u term is linear in C): the network's sums, in float per
  // species, must give the one-species result to float round-off of the rates.
  for (const Scheme scheme : {Scheme::modern, Scheme::conventional}) {
    const Case net = network_channel(scheme, Flow::wcsph, 3.0);
    Case one = testing::short_channel(scheme, Flow::wcsph);
    one.species.k = 0.0;
    one.species.c_in = one.species.c_init = 2.0;
    SphSolver a(net), b(one);
    const double dt = a.dt_limits().chosen;
    ASSERT_EQ(dt, b.dt_limits().chosen);
    for (int i = 0; i < 200; ++i) {
      ASSERT_TRUE(a.step(dt)) << a.failure();
      ASSERT_TRUE(b.step(dt)) << b.failure();
    }
    const ParticleStore &pa = a.particles(), &pb = b.particles();
    ASSERT_EQ(pa.size(), pb.size());
    double dev = 0.0, spread = 0.0;
    for (std::size_t i = 0; i < pa.size(); ++i) {
      if (pa.kind[i] != kFluidByte) continue;
      ASSERT_EQ(pa.x[i], pb.x[i]);  // the flow does not see the species
      dev = std::max(dev, std::fabs(pa.c[i] + pa.c_more[1][i] - pb.c[i]));
      spread = std::max(spread, std::fabs(pb.c[i] - 2.0));
    }
    std::printf("  %s: max |(A + P) - C_one| = %.2e (C_one - 2 up to %.2e)\n", to_string(scheme),
                dev, spread);
    EXPECT_GT(spread, 1e-6);  // the dilatation term has acted
    EXPECT_LT(dev, 1e-5 * spread + 1e-12);
  }
}

class NetworkRecorder : public RunObserver {
 public:
  explicit NetworkRecorder(long stop_at) : stop_at_(stop_at) {}
  void on_fields(const FieldFrame& f) override {
    c.assign(f.c.begin(), f.c.end());
    more.clear();
    for (const auto& [name, v] : f.more_c) more.emplace_back(v.begin(), v.end());
  }
  CheckpointRequest checkpoint_request(double) override {
    return ++calls_ == stop_at_ ? CheckpointRequest::write_and_stop : CheckpointRequest::none;
  }
  void on_checkpoint(const RunCheckpoint& cp) override { checkpoint = cp; }
  std::vector<double> c;
  std::vector<std::vector<double>> more;
  std::optional<RunCheckpoint> checkpoint;

 private:
  long stop_at_, calls_ = 0;
};

TEST(ReactionNetwork, RestartIsExact) {
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  Case c = network_channel(Scheme::modern, Flow::wcsph, 3.0);
  c.time.max_steps = 160;
  c.time.check_interval = 0.002;
  c.time.stop_when_steady = false;
  c.output.outlet_interval = 0.001;
  NetworkRecorder whole(0);
  const RunResult a = run_simulation(c, whole);
  ASSERT_EQ(a.status, "ok") << a.message;
  ASSERT_EQ(a.more_species.size(), 2u);
  EXPECT_EQ(a.more_species[1].name, "P");
  EXPECT_GT(a.more_species[1].stations.c_mean.back(), 0.0);

  NetworkRecorder first(60);
  ASSERT_EQ(run_simulation(c, first).status, "interrupted");
  ASSERT_TRUE(first.checkpoint.has_value());
  test::TempDir dir;
  CheckpointFile file;
  file.state = *first.checkpoint;
  file.case_text = "name = \"x\"\n";
  write_checkpoint(dir / "cp.h5", file);
  const CheckpointFile read = read_checkpoint(dir / "cp.h5");
  NetworkRecorder second(0);
  const RunResult b = run_simulation(c, second, &read.state);
  ASSERT_EQ(b.status, "ok") << b.message;
  EXPECT_EQ(whole.c, second.c);
  ASSERT_EQ(second.more.size(), 2u);
  EXPECT_EQ(whole.more, second.more);
  for (std::size_t s = 0; s < 2; ++s)
    EXPECT_EQ(a.more_species[s].stations.c_mean, b.more_species[s].stations.c_mean);
  // The outlet series of every species, split from the one series the checkpoint keeps.
  ASSERT_EQ(a.more_outlet.size(), 2u);
  ASSERT_GE(a.outlet.size(), 10u);  // one sample per 1 ms over 160 steps
  ASSERT_EQ(b.more_outlet.size(), 2u);
  for (std::size_t s = 0; s < 2; ++s) {
    ASSERT_EQ(a.more_outlet[s].size(), a.outlet.size());
    ASSERT_EQ(b.more_outlet[s].size(), a.outlet.size());
    for (std::size_t i = 0; i < a.outlet.size(); ++i) {
      EXPECT_EQ(a.more_outlet[s][i].t, a.outlet[i].t);
      EXPECT_EQ(a.more_outlet[s][i].c_flow, b.more_outlet[s][i].c_flow);
    }
  }
  // run.json's species_balance: every species' ledger, carried through the checkpoint.
  ASSERT_EQ(a.species_balance.size(), 3u);
  ASSERT_EQ(b.species_balance.size(), 3u);
  for (std::size_t s = 0; s < 3; ++s) {
    EXPECT_EQ(a.species_balance[s].name, b.species_balance[s].name);
    EXPECT_EQ(a.species_balance[s].inflow, b.species_balance[s].inflow) << s;
    EXPECT_EQ(a.species_balance[s].outflow, b.species_balance[s].outflow) << s;
    EXPECT_EQ(a.species_balance[s].reacted, b.species_balance[s].reacted) << s;
    EXPECT_EQ(a.species_balance[s].held, b.species_balance[s].held) << s;
  }
  EXPECT_GT(a.species_balance[0].inflow, 0.0);
  EXPECT_GT(a.species_balance[0].reacted, 0.0);  // the reactant is consumed
  EXPECT_LT(a.species_balance[2].reacted, 0.0);  // the product made
  EXPECT_GT(a.balance_flow_rate, 0.0);
  // At the start the outlet holds the initial fluid: B at 1.5, P at 0.
  EXPECT_NEAR(a.more_outlet[0].front().c_flow, 1.5, 1e-6);
  EXPECT_NEAR(a.more_outlet[1].front().c_flow, 0.0, 1e-6);
  omp_set_num_threads(threads);
}

}  // namespace
}  // namespace adrsph
