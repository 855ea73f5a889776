// The WCSPH flow in the channel: Poiseuille profile kept, mass bookkeeping, robustness.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "adrsph/simulation.hpp"
#include "boundaries/channel_scene.hpp"
#include "integrator/sph_solver.hpp"
#include "integrator/time_step.hpp"
#include "particles/particle_store.hpp"
#include "sph_test_cases.hpp"

namespace adrsph {
namespace {

// L2 error of the fluid velocity against u(y) = u_max (1 - (y/R)^2), relative to the L2 norm
// of the profile.
double poiseuille_l2_error(const SphSolver& s, const Case& c) {
  const auto& p = s.particles();
  double err = 0, norm = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind[i] != kFluidByte) continue;
    const double eta = p.y[i] / c.geometry.half_width;
    const double u = c.u_max() * (1 - eta * eta);
    err += (p.vx[i] - u) * (p.vx[i] - u) + p.vy[i] * p.vy[i];
    norm += u * u;
  }
  return std::sqrt(err / norm);
}

TEST(Flow, ModernSchemeKeepsPoiseuilleProfile) {
  Case c = testing::short_channel(Scheme::modern, Flow::wcsph, 20.0);
  SphSolver solver(c);
  const double dt = solver.dt_limits().chosen;
  while (solver.time() < 0.1) ASSERT_TRUE(solver.step(dt)) << solver.failure();
  const double err = poiseuille_l2_error(solver, c);
  std::printf("modern scheme, t = %.3f s: L2 velocity error %.3f%%\n", solver.time(), 100 * err);
  EXPECT_LT(err, 0.02);
}

TEST(Flow, ConventionalSchemeKeepsPoiseuilleProfile) {
  Case c = testing::short_channel(Scheme::conventional, Flow::wcsph, 20.0);
  SphSolver solver(c);
  const double dt = solver.dt_limits().chosen;
  while (solver.time() < 0.1) ASSERT_TRUE(solver.step(dt)) << solver.failure();
  const double err = poiseuille_l2_error(solver, c);
  std::printf("conventional scheme, t = %.3f s: L2 velocity error %.3f%%\n", solver.time(),
              100 * err);
  EXPECT_LT(err, 0.05);
}

// d(rho/rho0)/dx of the fluid [1/mm]: least-squares slope over x in [x0, x1].
double density_slope(const SphSolver& s, const Case& c, double x0, double x1) {
  const auto& p = s.particles();
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind[i] != kFluidByte || p.x[i] < x0 || p.x[i] > x1) continue;
    const double r = p.rho[i] / c.fluid.rho0 - 1.0;
    n += 1;
    sx += p.x[i];
    sy += r;
    sxx += p.x[i] * p.x[i];
    sxy += p.x[i] * r;
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

// fluid.driving: driven by the pressure difference (the paper's set-up), the density falls
// along the channel by the Poiseuille pressure gradient over c0^2, -2 nu u_max / (R^2 c0^2)
// per mm (docs/compressibility.md); driven by the body force that equals that gradient, the
// same flow keeps a uniform density and the same profile.
TEST(Flow, BodyForceDrivingLeavesTheDensityUniform) {
  for (Scheme scheme : {Scheme::modern, Scheme::conventional}) {
    Case c = testing::short_channel(scheme, Flow::wcsph, 20.0);
    const double r = c.geometry.half_width;
    const double expected = -2.0 * c.fluid.nu * c.u_max() / (r * r * c.c0() * c.c0());
    double slope[2], err[2];
    for (Driving d : {Driving::pressure, Driving::body_force}) {
      c.fluid.driving = d;
      SphSolver solver(c);
      const double dt = solver.dt_limits().chosen;
      // The slope averaged over t in [0.05, 0.1] s: the start's acoustic waves still swing it.
      double sum = 0.0;
      int samples = 0;
      for (long step = 0; solver.time() < 0.1; ++step) {
        ASSERT_TRUE(solver.step(dt)) << solver.failure();
        if (solver.time() >= 0.05 && step % 10 == 0) {
          sum += density_slope(solver, c, 3.0, 17.0);
          ++samples;
        }
      }
      const int k = d == Driving::body_force;
      slope[k] = sum / samples;
      err[k] = poiseuille_l2_error(solver, c);
    }
    std::printf(
        "%s: d(rho/rho0)/dx %.3e /mm driven by pressure, %.3e by the body force "
        "(Poiseuille %.3e); L2 velocity error %.3f%% / %.3f%%\n",
        scheme == Scheme::modern ? "modern" : "conventional", slope[0], slope[1], expected,
        100 * err[0], 100 * err[1]);
    EXPECT_NEAR(slope[0], expected, 0.1 * std::fabs(expected));
    EXPECT_LT(std::fabs(slope[1]), 0.05 * std::fabs(expected));
    EXPECT_LT(err[1], 0.02);
  }
}

// The conventional force pass also sums the kernel at the positions the integrator gives the
// particles next, and the next evaluation takes its density from there instead of a pass of
// its own (pass_context.hpp). Both ways must give the same run to round-off: through list
// rebuilds, particles entering from the inflow buffer and leaving at the outlet.
TEST(Flow, ConventionalPredictedDensityIsTheSummationDensity) {
  Case c = testing::short_channel(Scheme::conventional, Flow::wcsph, 5.0);
  c.particles.skin = 0.02;  // rebuilds every few steps
  SphSolver fused(c), separate(c);
  separate.predict_density(false);
  const double dt = fused.dt_limits().chosen;
  for (int k = 0; k < 150; ++k) {
    ASSERT_TRUE(fused.step(dt)) << fused.failure();
    ASSERT_TRUE(separate.step(dt)) << separate.failure();
  }
  EXPECT_GT(fused.list_rebuilds(), 10);
  EXPECT_GT(fused.boundary_crossings().entered, 0);
  EXPECT_GT(fused.boundary_crossings().left, 0);
  const auto& a = fused.particles();
  const auto& b = separate.particles();
  ASSERT_EQ(a.size(), b.size());
  double dpos = 0, dvel = 0, drho = 0, dc = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    dpos = std::max({dpos, std::fabs(a.x[i] - b.x[i]), std::fabs(a.y[i] - b.y[i])});
    dvel = std::max({dvel, std::fabs(a.vx[i] - b.vx[i]), std::fabs(a.vy[i] - b.vy[i])});
    drho = std::max(drho, std::fabs(a.rho[i] / b.rho[i] - 1.0));
    dc = std::max(dc, std::fabs(a.c[i] - b.c[i]));
  }
  std::printf(
      "fused vs separate summation density after 150 steps: |dx| %.1e mm, |du| %.1e mm/s, "
      "|drho/rho| %.1e, |dC| %.1e\n",
      dpos, dvel, drho, dc);
  // Single-precision rounding of the separation: rho may differ by ~16 float epsilons (1e-6),
  // not more (a separation error of 1e-3 dx would move it by ~1e-3). What that allows
  // downstream: a pressure difference c0^2 rho0 1e-6 over h accelerates by at most
  // c0^2 1e-6 / h for the time t, and moves by that times t; C by 1e-6 of c_in.
  const double t = fused.time(), dvel_bound = c.c0() * c.c0() * 1e-6 / c.h() * t;
  EXPECT_LT(drho, 1e-6);
  EXPECT_LT(dvel, dvel_bound);
  EXPECT_LT(dpos, dvel_bound * t);
  EXPECT_LT(dc, 1e-6 * c.species.c_in);
}

// Particles of two stores of the same size whose state (x, u, rho, C) is not bit for bit the same.
std::size_t state_differences(const ParticleStore& a, const ParticleStore& b) {
  std::size_t differ = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    differ += a.x[i] != b.x[i] || a.y[i] != b.y[i] || a.vx[i] != b.vx[i] || a.vy[i] != b.vy[i] ||
              a.rho[i] != b.rho[i] || a.c[i] != b.c[i];
  return differ;
}

// Watching a run does not change it: sampling the probes reads the particles on the grid of
// the last sort and never re-sorts them, so a run sampled every step ends bit for bit where
// an unobserved one does, with the same list rebuilds.
TEST(Flow, WatchingDoesNotChangeTheRun) {
  Case c = testing::short_channel(Scheme::modern, Flow::wcsph, 10.0);
  SphSolver watched(c), alone(c);
  const double dt = watched.dt_limits().chosen;
  double sampled = 0.0;
  for (int k = 0; k < 300; ++k) {
    ASSERT_TRUE(watched.step(dt)) << watched.failure();
    ASSERT_TRUE(alone.step(dt)) << alone.failure();
    sampled += watched.sampler().section_average(5.0, c.geometry.half_width, 10);
  }
  EXPECT_TRUE(std::isfinite(sampled));
  EXPECT_GT(alone.list_rebuilds(), 3);
  EXPECT_EQ(watched.list_rebuilds(), alone.list_rebuilds());
  ASSERT_EQ(watched.particles().size(), alone.particles().size());
  EXPECT_EQ(state_differences(watched.particles(), alone.particles()), 0u);
  // And the sample is the one a freshly sorted grid gives (the search found every particle).
  const double before = alone.sampler().section_average(5.0, c.geometry.half_width, 10);
  alone.rebuild();
  EXPECT_NEAR(alone.sampler().section_average(5.0, c.geometry.half_width, 10), before,
              1e-12 * std::fabs(before));
}

// Giving the force pass's records back before a write (SphSolver::shed_for_output, as the run
// loop does at each field frame and checkpoint) does not change the run: the next pass refills
// them from the state. They come back at least at the size they had (a refill at a smaller
// particle count would otherwise double the block at the next larger one).
TEST(Flow, GivingTheRecordsBackForAWriteDoesNotChangeTheRun) {
  for (Scheme scheme : {Scheme::modern, Scheme::conventional}) {
    Case c = testing::short_channel(scheme, Flow::wcsph, 10.0);
    SphSolver shed(c), kept(c);
    const double dt = shed.dt_limits().chosen;
    int writes = 0;
    for (int k = 0; k < 120; ++k) {
      ASSERT_TRUE(shed.step(dt)) << shed.failure();
      ASSERT_TRUE(kept.step(dt)) << kept.failure();
      if (k % 7 != 0) continue;
      const std::size_t held = shed.pair_record_bytes();
      ASSERT_GT(held, 0u);
      shed.shed_for_output();
      EXPECT_EQ(shed.pair_record_bytes(), 0u);
      ASSERT_TRUE(shed.step(dt)) << shed.failure();
      ASSERT_TRUE(kept.step(dt)) << kept.failure();
      EXPECT_GE(shed.pair_record_bytes(), held);
      ++writes;
    }
    EXPECT_GT(writes, 10);
    EXPECT_GT(kept.list_rebuilds(), 3);
    EXPECT_EQ(shed.list_rebuilds(), kept.list_rebuilds());
    ASSERT_EQ(shed.particles().size(), kept.particles().size());
    EXPECT_EQ(state_differences(shed.particles(), kept.particles()), 0u)
        << (scheme == Scheme::modern ? "modern" : "conventional");
  }
}

TEST(Flow, FluidMassChangesOnlyByCrossings) {
  // All particles carry the one mass of the store (ParticleStore::mass, a single number), so
  // the fluid mass is m N_fluid, and it changes only by particles crossing the inlet and
  // outlet planes: N_fluid(t) = N_fluid(0) + in - out, none lost on the way.
  Case c = testing::short_channel(Scheme::modern, Flow::wcsph, 20.0);
  SphSolver solver(c);
  const long n0 = static_cast<long>(solver.fluid_count());
  const double dt = solver.dt_limits().chosen;
  while (solver.time() < 0.05) ASSERT_TRUE(solver.step(dt)) << solver.failure();
  const auto& flux = solver.boundary_crossings();
  EXPECT_GT(flux.entered, 0);
  EXPECT_GT(flux.left, 0);
  EXPECT_EQ(static_cast<long>(solver.fluid_count()), n0 + flux.entered - flux.left);
  EXPECT_EQ(solver.lost_particles(), 0);
}

// The outflow buffer carries the background state (p_b at rho0) that the walls near the
// outlet sample: each scheme's density pass sets it before the boundary pass reads it
// (density_passes.hpp, outflow_state), whatever the buffer held before.
TEST(Flow, OutflowBufferGetsTheBackgroundStateAtEachEvaluation) {
  for (Scheme scheme : {Scheme::modern, Scheme::conventional}) {
    SphSolver solver(testing::short_channel(scheme, Flow::wcsph, 20.0));
    ParticleStore& s = solver.particles();
    int outlet = 0;
    for (std::size_t i = 0; i < s.size(); ++i)
      if (s.kind[i] == kOutletByte) {
        s.p[i] = 123.0f;  // what a fluid particle may carry as it crosses
        s.rho[i] = 1.5 * solver.physics().eos.rho0;
        ++outlet;
      }
    ASSERT_GT(outlet, 0);
    solver.evaluate();
    const TaitEos& eos = solver.physics().eos;
    for (std::size_t i = 0; i < s.size(); ++i) {
      if (s.kind[i] != kOutletByte) continue;
      ASSERT_EQ(s.p[i], static_cast<float>(eos.p_background)) << i;
      ASSERT_EQ(s.rho[i], eos.rho0) << i;
      ASSERT_EQ(s.volume(i), static_cast<float>(s.mass / eos.rho0)) << i;
    }
  }
}

class LastFrame : public RunObserver {
 public:
  void on_fields(const FieldFrame& f) override {
    calls++;
    all_finite = true;
    for (double v : f.vx) all_finite = all_finite && std::isfinite(v);
    for (double v : f.c) all_finite = all_finite && std::isfinite(v);
  }
  int calls = 0;
  bool all_finite = false;
};

TEST(Robustness, StepAboveStableLimitIsCaught) {
  Case c = testing::short_channel(Scheme::modern, Flow::wcsph, 20.0);
  c.time.dt = 20 * 0.25 * c.h() / (c.c0() + c.u_max());  // 20x the acoustic limit
  c.time.t_end = 0.5;
  LastFrame obs;
  const RunResult r = run_simulation(c, obs);
  EXPECT_EQ(r.status, "failed");
  EXPECT_NE(r.message.find("time.cfl"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("time.dt"), std::string::npos) << r.message;
  EXPECT_LT(r.t_reached, c.time.t_end);
  EXPECT_GE(obs.calls, 1);
  EXPECT_TRUE(obs.all_finite) << "the last good state must be written, not the blown-up one";
}

// A warm start whose prescribed-flow run trips a guard stops the run (no half-made initial
// field); a fixed step factor of a stability study leaves the warm start's own step alone.
TEST(Robustness, WarmStartFailsLoudlyAndKeepsItsOwnStep) {
  Case c = testing::short_channel(Scheme::modern, Flow::wcsph, 10.0);
  c.time.warm_start = true;
  c.time.t_end = 0.05;
  c.output.field_times = {};
  Case bad = c;
  bad.species.D = 1000.0;
  bad.species.c_init = 0.0;
  bad.time.species_subcycling = false;
  bad.time.diffusion_number = 5.0;  // 20x the explicit limit (validation would refuse it)
  LastFrame obs;
  try {
    run_simulation(bad, obs);
    ADD_FAILURE() << "the failed warm start went unnoticed";
  } catch (const WarmStartFailed& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("warm start"), std::string::npos) << what;
    EXPECT_NE(what.find("concentration"), std::string::npos) << what;
    EXPECT_NE(what.find("time.warm_start = false"), std::string::npos) << what;
  }
  const RunResult plain = run_simulation(c, obs);
  c.time.dt_factor = 2.0;
  const RunResult fixed = run_simulation(c, obs);
  EXPECT_EQ(plain.warm_start_steps, fixed.warm_start_steps);
  EXPECT_GT(fixed.warm_start_steps, 0);
  EXPECT_DOUBLE_EQ(fixed.dt.chosen, 2.0 * plain.dt.chosen);
}

// A step that trips a guard is undone: the particles, their kinds, the inflow rows (seen
// through the next steps), the ledger, the crossings and the time are as before it. The
// particle state goes back through the step's own rates (integrator/midpoint.hpp), exact to
// the rounding of one addition: positions and C within 1e-10 of the twin's (the rounding is
// ~1e-13 here; a missed term of the undo would be off by the step's change, 1e-2 or more).
TEST(Robustness, FailedStepLeavesEverythingAsItWas) {
  Case c = testing::short_channel(Scheme::modern, Flow::prescribed, 10.0);
  c.species.D = 1000.0;
  c.species.c_init = 0.0;  // a front at the inlet: explicit diffusion far too long blows up
  c.time.species_subcycling = false;
  SphSolver solver(c), twin(c);
  solver.track_species_balance(true);
  twin.track_species_balance(true);
  const double dt = solver.dt_limits().chosen;
  for (int k = 0; k < 5; ++k) {
    ASSERT_TRUE(solver.step(dt)) << solver.failure();
    ASSERT_TRUE(twin.step(dt)) << twin.failure();
  }
  const double huge = 200.0 * dt;  // moves the inlet rows into the fluid, C far off its band
  ASSERT_FALSE(solver.step(huge));
  EXPECT_NE(solver.failure().find("concentration"), std::string::npos) << solver.failure();
  // Where and what: the step that failed, and a particle inside the channel (its last good
  // position) whose C left the band by more than the guard's margin.
  const SphSolver::FailureSite& site = solver.failure_site();
  EXPECT_EQ(site.kind, FailureKind::concentration);
  EXPECT_EQ(site.step, twin.steps() + 1);
  EXPECT_DOUBLE_EQ(site.t, twin.time() + huge);
  EXPECT_GT(site.value, 0.5 * c.species.c_in);
  EXPECT_LE(std::fabs(site.y), c.geometry.half_width);
  EXPECT_NE(solver.failure().find("(x, y) = ("), std::string::npos) << solver.failure();
  EXPECT_EQ(solver.time(), twin.time());
  EXPECT_EQ(solver.steps(), twin.steps());
  const auto& l = solver.species_ledger();
  const auto& m = twin.species_ledger();
  EXPECT_EQ(l.inflow, m.inflow);
  EXPECT_EQ(l.outflow, m.outflow);
  EXPECT_EQ(l.buffer_exchange, m.buffer_exchange);
  EXPECT_EQ(l.reaction, m.reaction);
  EXPECT_EQ(solver.boundary_crossings().entered, twin.boundary_crossings().entered);
  EXPECT_EQ(solver.boundary_crossings().left, twin.boundary_crossings().left);
  // The state, and everything that follows from it: the next steps match the twin's.
  for (int k = 0; k < 5; ++k) {
    ASSERT_TRUE(solver.step(dt)) << solver.failure();
    ASSERT_TRUE(twin.step(dt)) << twin.failure();
  }
  const auto& a = solver.particles();
  const auto& b = twin.particles();
  ASSERT_EQ(a.size(), b.size());
  std::size_t differ = 0;
  double off = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    differ += a.kind[i] != b.kind[i];
    off = std::max({off, std::fabs(a.x[i] - b.x[i]), std::fabs(a.y[i] - b.y[i]),
                    std::fabs(a.c[i] - b.c[i]) / c.species.c_in});
  }
  EXPECT_EQ(differ, 0u);
  EXPECT_LT(off, 1e-10) << "largest difference in x, y [mm] or C / c_in";
  EXPECT_EQ(solver.boundary_crossings().entered, twin.boundary_crossings().entered);
}

TEST(Robustness, JitteredLatticeStaysStableWithShifting) {
  Case c = testing::short_channel(Scheme::modern, Flow::wcsph, 20.0);
  c.particles.jitter = 0.2;  // every fluid particle up to 0.2 dx off its site in x and y
  SphSolver solver(c);
  const double dt = solver.dt_limits().chosen;
  while (solver.time() < 0.1) ASSERT_TRUE(solver.step(dt)) << solver.failure();
  const double err = poiseuille_l2_error(solver, c);
  std::printf("jittered start, modern, t = %.3f s: L2 velocity error %.3f%%\n", solver.time(),
              100 * err);
  EXPECT_LT(err, 0.10);
  EXPECT_EQ(solver.lost_particles(), 0);
}

TEST(Robustness, LostParticleStopsTheRunWithAMessage) {
  Case c = testing::short_channel(Scheme::modern, Flow::wcsph, 20.0);
  SphSolver solver(c);
  auto& p = solver.particles();
  const std::size_t n_fluid = solver.fluid_count();
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (p.kind[i] != kFluidByte) continue;
    p.y[i] = c.geometry.half_width + 1.5 * c.particles.dx;  // inside the wall layers
    break;
  }
  solver.rebuild();  // finds it beyond the wall and removes it
  EXPECT_EQ(solver.lost_particles(), 1);
  EXPECT_EQ(solver.fluid_count(), n_fluid - 1);
  EXPECT_FALSE(solver.step(solver.dt_limits().chosen));
  EXPECT_NE(solver.failure().find("left the channel"), std::string::npos) << solver.failure();
  EXPECT_EQ(solver.failure_site().kind, FailureKind::lost_particles);
  EXPECT_EQ(solver.failure_site().value, 1.0);
  const std::string advice = failure_advice(solver.failure_kind(), c, 0.0);
  EXPECT_NE(advice.find("time.cfl"), std::string::npos) << advice;
}

// particles.jitter moves the fluid particles only, by at most jitter dx in x and y, and the
// same way every time (the stability map compares runs that differ in one key).
TEST(Robustness, JitterMovesOnlyTheFluidWithinItsBound) {
  Case c = testing::short_channel(Scheme::modern, Flow::wcsph, 20.0);
  ParticleStore a, b, again;  // the scene's start, before any sort: same order
  ChannelScene(c).initialise(a);
  c.particles.jitter = 0.3;
  ChannelScene(c).initialise(b);
  ChannelScene(c).initialise(again);
  ASSERT_EQ(a.size(), b.size());
  double largest = 0.0;
  std::size_t moved = 0, fluid = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double d = std::max(std::fabs(b.x[i] - a.x[i]), std::fabs(b.y[i] - a.y[i]));
    if (a.kind[i] != kFluidByte) {
      EXPECT_EQ(d, 0.0) << "a boundary particle moved";
      continue;
    }
    ++fluid;
    largest = std::max(largest, d);
    moved += d > 0.0;
    EXPECT_EQ(b.x[i], again.x[i]);
    EXPECT_EQ(b.y[i], again.y[i]);
  }
  EXPECT_LE(largest, 0.3 * c.particles.dx);
  EXPECT_GT(largest, 0.25 * c.particles.dx);  // the offsets fill their range
  EXPECT_EQ(moved, fluid);
}

// The conventional scheme's summation density sees a disordered start at once: a lattice
// jittered by 0.3 dx is more than 20% off rho0 somewhere, and the density guard stops the
// first step, with advice about the start rather than the step.
TEST(Robustness, DisorderedStartFailsTheFirstConventionalStep) {
  Case c = testing::short_channel(Scheme::conventional, Flow::wcsph, 20.0);
  c.particles.jitter = 0.3;
  SphSolver solver(c);
  ASSERT_FALSE(solver.step(solver.dt_limits().chosen));
  const SphSolver::FailureSite& site = solver.failure_site();
  EXPECT_EQ(site.kind, FailureKind::density);
  EXPECT_EQ(site.step, 1);
  EXPECT_GT(site.value, 0.2);
  EXPECT_NE(solver.failure().find("first step"), std::string::npos) << solver.failure();
  const std::string advice = failure_advice(site.kind, c, 0.0, site.step == 1);
  EXPECT_NE(advice.find("particles.jitter"), std::string::npos) << advice;
  EXPECT_EQ(failure_advice(site.kind, c, 0.0, false).find("particles.jitter"), std::string::npos);
}

// time.dt_factor fixes the step at a multiple of the case's own limit, without sub-cycling.
TEST(Robustness, DtFactorIsAMultipleOfTheLimit) {
  Case c = testing::short_channel(Scheme::modern, Flow::wcsph, 20.0);
  c.species.D = 1e4;  // the diffusion limit binds (9x below the acoustic) and is sub-cycled
  const TimeStepLimits natural = time_step_limits(c);
  ASSERT_GT(natural.diffusion_stages, 1);
  c.time.dt_factor = 2.0;
  const TimeStepLimits fixed = time_step_limits(c);
  EXPECT_EQ(fixed.diffusion_stages, 1);
  EXPECT_DOUBLE_EQ(fixed.chosen, 2.0 * natural.diffusion);
  EXPECT_NE(fixed.binding.find("time.dt_factor"), std::string::npos) << fixed.binding;
}

}  // namespace
}  // namespace adrsph
