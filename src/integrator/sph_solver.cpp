#include "integrator/sph_solver.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <stdexcept>
#include <string>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include "boundaries/boundary_extrapolation.hpp"
#include "integrator/midpoint.hpp"
#include "integrator/time_step.hpp"
#include "schemes/density_passes.hpp"
#include "schemes/interaction_pass.hpp"
#include "schemes/scheme_traits.hpp"
#include "species/feed_integral.hpp"
#include "species/inlet_feed.hpp"
#include "species/reaction_kinetics.hpp"
#include "species/wall_images.hpp"

namespace adrsph {

SphSolver::SphSolver(const Case& c) : SphSolver(c, {}) {}

SphSolver::SphSolver(const Case& c, std::span<const double> initial_c)
    : case_(c), scene_(c), kernel_(c.h()) {
  const double h = c.h();
  phys_.eta2 = 0.01 * h * h;
  phys_.four_nu = 4.0 * c.fluid.nu;
  phys_.delta_h_c0_2 = 2.0 * c.modern.delta * h * c.c0();
  phys_.diffusivity = c.species.D;
  phys_.body_force_x = c.body_force_x();
  phys_.max_diffusivity = c.species.D;
  phys_.wall_image_y = c.particles.wall_images ? c.geometry.half_width : 0.0;
  for (int e = 0; e + 1 < c.species_count(); ++e) {
    phys_.more_diffusivity[static_cast<std::size_t>(e)] = c.more_species[e].D;
    phys_.max_diffusivity = std::max(phys_.max_diffusivity, c.more_species[e].D);
  }
  phys_.eos.rho0 = c.fluid.rho0;
  phys_.eos.c0 = c.c0();
  phys_.eos.gamma = c.fluid.gamma;
  phys_.eos.p_background = c.scheme == Scheme::conventional
                               ? c.fluid.background_pressure * c.fluid.rho0 * c.c0() * c.c0()
                               : 0.0;
  limits_ = time_step_limits(c);

  skin_ = c.particles.skin * kernel_.support;
  cutoff_ = kernel_.support + skin_;
  // The most upstream inlet particle sits at most (inlet_layers - 1.5) dx upstream of x = 0
  // after a feed; the fluid needs particles down to -3 dx (channel_scene.cpp).
  abs_limit_ = std::max(0.0, (c.particles.inlet_layers - 4.5) * c.particles.dx);
  grid_ = CellGrid(scene_.xmin() - cutoff_, scene_.xmax() + cutoff_, scene_.ymin() - cutoff_,
                   scene_.ymax() + cutoff_, cutoff_);

  const bool split = limits_.diffusion_stages > 1;
  const bool net = c.species_count() > 1;
  if (c.flow == Flow::prescribed)
    net ? bind<PrescribedFlow, false, true>(split) : bind<PrescribedFlow, false, false>(split);
  else if (c.scheme == Scheme::conventional)
    net ? bind<ConventionalScheme, false, true>(split)
        : bind<ConventionalScheme, false, false>(split);
  else if (c.species.ale)  // one species only (case_validate.cpp)
    bind<ModernScheme, true, false>(split);
  else
    net ? bind<ModernScheme, false, true>(split) : bind<ModernScheme, false, false>(split);

  scene_.initialise(store_);
  if (!initial_c.empty()) {
    if (initial_c.size() != store_.size())
      throw std::invalid_argument("initial concentration field has " +
                                  std::to_string(initial_c.size()) + " values for " +
                                  std::to_string(store_.size()) + " particles");
    for (std::size_t i = 0; i < store_.size(); ++i) store_.c[i] = initial_c[i];
  }
  for (std::size_t i = 0; i < store_.size(); ++i) store_.p[i] = phys_.eos.p_background;
  apply_feed(0.0, 0.0);  // (only species whose feed varies)
  rebuild();
}

double SphSolver::species_inventory(int species) const {
  const std::vector<double>& c = store_.concentration(species);
  double total = 0.0;
  for (std::size_t i = 0; i < store_.size(); ++i)
    if (store_.kind[i] == kFluidByte) total += store_.mass / store_.rho[i] * c[i];
  return total;
}

template <class S, bool Ale, bool Net>
void SphSolver::bind(bool split) {
  step_fn_ =
      split ? &SphSolver::step_impl<S, Ale, true, Net> : &SphSolver::step_impl<S, Ale, false, Net>;
  eval_fn_ = split ? &SphSolver::evaluate_at_rest<S, Ale, true, Net>
                   : &SphSolver::evaluate_at_rest<S, Ale, false, Net>;
  // The arrays S uses, and one set per species of the network; no more. Sub-cycled diffusion
  // changes C after the transport: then C's start value is kept, not its first-stage rate.
  store_.set_needs({S::momentum, S::continuity, S::shifting, case_.species_count() - 1, split,
                    S::summation_density});
}

std::size_t SphSolver::fluid_count() const {
  std::size_t n = 0;
  for (std::size_t i = 0; i < store_.size(); ++i) n += store_.kind[i] == kFluidByte;
  return n;
}

void SphSolver::rebuild() {
  // The sort's order is kept in the displacement monitor's array (one 32-bit word per
  // particle, dead until the monitor is reset after the list build): a re-sort allocates
  // nothing per particle but the permutation's cycle leaders and a bit per particle.
  std::vector<std::uint32_t> order = monitor_.release_storage();
  {
    ScopedPhase timer(timers_, Phase::sort);
    std::vector<std::uint32_t> outside;
    const std::size_t capacity = store_.capacity();
    scene_.feed_and_drain(store_, lost_);  // removed particles get x = NaN
    // The store grew (the fluid compresses as the pressure gradient builds up): its fields
    // were moved one by one, and the holes they left in the heap (one field, ~0.6 MB at fine
    // resolution) would stay resident.
    if (store_.capacity() != capacity) trim_heap();
    const std::size_t n = store_.size();
    if (order.capacity() < n) {  // more particles than at the last build: headroom as the store
      std::vector<std::uint32_t>().swap(order);
      order.reserve(ParticleStore::grown_capacity(n));
    }
    // Removed particles are outside the grid (x = NaN), so the counting sort drops them.
    grid_.sort(std::span(store_.x).first(n), std::span(store_.y).first(n), order, outside);
    for (std::uint32_t i : outside)
      if (std::isfinite(store_.x[i]) && store_.kind[i] == kFluidByte) ++lost_;
    store_.permute(order);
  }
  {
    ScopedPhase timer(timers_, Phase::neighbours);
    const std::size_t n = store_.size();
    list_.build(grid_, std::span(store_.x).first(n), std::span(store_.y).first(n), cutoff_,
                static_cast<std::uint32_t>(n), NeighbourList::Width::automatic, wall_rows());
    monitor_.reset(grid_, std::span(store_.x).first(n), std::span(store_.y).first(n),
                   std::move(order));
  }
  moved_abs_ = 0.0;
  // density_predicted_ stays: the predictions moved with their particles, and a particle fed
  // into the inflow buffer has none (NaN). The re-sort follows a step that may have moved a
  // pair up to one step's relative motion inside the support past the list's skin (the
  // monitor's test is taken after the step); such a pair enters the kernel sum at the very
  // edge of the support, where W ~ (3 - q)^5 is below the float rounding of the sum
  // (Flow.ConventionalPredictedDensityIsTheSummationDensity).
  ++rebuilds_;
  if (!list_.one_pass()) ++two_pass_builds_;
}

bool SphSolver::needs_rebuild() {
  if (moved_abs_ > abs_limit_) return true;
  if (2.0 * moved_abs_ <= skin_) return false;  // no particle moved skin/2: nothing to check
  ScopedPhase timer(timers_, Phase::neighbours);
  const std::size_t n = store_.size();
  return monitor_.max_closing(grid_, std::span(store_.x).first(n), std::span(store_.y).first(n),
                              cutoff_, moved_abs_) > skin_;
}

void SphSolver::evaluate() {
  density_predicted_ = false;
  (this->*eval_fn_)();
  density_predicted_ = false;  // it predicted for positions no step will produce
}

namespace {
// The displacement of the first stage of particle i, d = a u (a = dt / 2), as advance<1>()
// will apply it (no shifting in the scheme that predicts). Walls do not move (0); a < 0: no
// prediction wanted (0).
struct NextDisplacement {
  const ParticleStore& s;
  float* dx;
  float* dy;
  double a;
  void operator()(std::size_t i) const {
    if (a < 0.0 || s.kind[i] == kWallByte) {
      dx[i] = dy[i] = 0.0f;
      return;
    }
    dx[i] = static_cast<float>(a * s.vx[i]);
    dy[i] = static_cast<float>(a * s.vy[i]);
  }
};
// evaluate_impl's a_next for the second stage: its displacement is written by advance<1>().
constexpr double kWrittenByFirstStage = std::numeric_limits<double>::quiet_NaN();
}  // namespace

template <class S, bool Ale, bool Split, bool Net>
void SphSolver::evaluate_impl(double a_next) {
  PassContext ctx{kernel_, list_, phys_};
  if constexpr (S::summation_density) {
    ScopedPhase timer(timers_, Phase::density);
    const std::size_t n = store_.size();
    for (auto* v : {&next_dx_, &next_dy_}) v->resize(n + 1);
    next_dx_[n] = next_dy_[n] = 0.0f;  // the padding particle
    // The displacements in the same loop as the densities: one pass over the store.
    float* sums = store_.predicted_density.data();
    const float* predicted = density_predicted_ ? sums : nullptr;
    if (std::isnan(a_next))  // kWrittenByFirstStage
      summation_density(store_, ctx, predicted, [](std::size_t) {});
    else
      summation_density(store_, ctx, predicted,
                        NextDisplacement{store_, next_dx_.data(), next_dy_.data(), a_next});
    ctx.next_density = {sums, next_dx_.data(), next_dy_.data()};
  }
  if constexpr (S::momentum) {
    if constexpr (!S::summation_density) {
      ScopedPhase timer(timers_, Phase::density);
      fluid_pressure(store_, phys_.eos);
    }
    ScopedPhase timer(timers_, Phase::boundaries);
    extrapolate_to_boundaries(store_, ctx);
  }
  ScopedPhase timer(timers_, Phase::forces);
  interaction_pass<S, Ale, !Split, Net>(store_, ctx, pair_records_);
  if (!Split && phys_.wall_image_y > 0.0) add_wall_image_diffusion(store_, ctx);
}

// Explicit midpoint (integrator/midpoint.hpp). Stage 1: q_h = q0 + dt/2 f(q0). Stage 2:
// q1 = q0 + dt f(q_h), q0 recovered from q_h and the first-stage rates. Positions move with
// the transport velocity of their stage (u + du for the fluid of a shifting scheme, eq. (10)).
// Non-finite rates count as zero and are added to bad_rates_ (the step then fails).
template <class S, int Stage, bool Net>
void SphSolver::advance(double dt) {
  using midpoint::rate_or_zero, midpoint::finite_rate;
  ScopedPhase timer(timers_, Phase::integration);
  ParticleStore& s = store_;
  const std::size_t n = s.size();
  const double h = 0.5 * dt;
  const double a = Stage == 1 ? h : dt;
  const bool keep_c = s.needs().species_start;
  const int more = Net ? s.needs().more_species : 0;
  long bad = 0;
#pragma omp parallel for schedule(static) reduction(+ : bad)
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t k = s.kind[i];
    if (k == kWallByte) continue;
    const bool fluid = k == kFluidByte;
    int nonfinite = 0;
    auto take = [&nonfinite](float r) {
      nonfinite += finite_rate(r) ? 0 : 1;
      return rate_or_zero(r);
    };
    // q0: the current state at stage 1; at stage 2 recovered, q0 = q_h - dt/2 f0.
    double x0 = s.x[i], y0 = s.y[i];
    double vx0 = s.vx[i], vy0 = s.vy[i];
    if constexpr (Stage == 2) {
      const midpoint::FirstStage f0 =
          midpoint::first_stage_velocity<S::momentum, S::shifting>(s, i, fluid, h, take);
      x0 -= h * f0.tx;
      y0 -= h * f0.ty;
      vx0 = f0.vx;
      vy0 = f0.vy;
    }
    if (fluid && S::momentum) {
      double tx = s.vx[i], ty = s.vy[i];
      if constexpr (S::shifting) {
        tx += take(s.sx[i]);
        ty += take(s.sy[i]);
      }
      s.x[i] = x0 + a * tx;
      s.y[i] = y0 + a * ty;
      s.vx[i] = vx0 + a * take(s.ax[i]);
      s.vy[i] = vy0 + a * take(s.ay[i]);
    } else {
      // Inlet (prescribed profile), outlet (frozen velocity), prescribed-flow fluid: u is
      // constant over the step.
      s.x[i] = x0 + a * s.vx[i];
      s.y[i] = y0 + a * s.vy[i];
    }
    if (fluid) {
      if constexpr (S::continuity) {
        double rho0 = s.rho[i];
        if constexpr (Stage == 2) rho0 -= h * take(s.drho_first[i]);
        s.rho[i] = rho0 + a * take(s.drho[i]);
      }
      double c0 = s.c[i];
      if (keep_c && Stage == 1) s.c_start[i] = c0;
      if (Stage == 2) c0 = keep_c ? s.c_start[i] : c0 - h * take(s.dc_first[i]);
      s.c[i] = c0 + a * take(s.dc[i]);
      if constexpr (Net)
        for (int e = 0; e < more; ++e) {
          double& ce = s.c_more[e][i];
          double ce0 = ce;
          if (keep_c && Stage == 1) s.c_more_start[e][i] = ce0;
          if (Stage == 2)
            ce0 = keep_c ? s.c_more_start[e][i] : ce0 - h * take(s.dc_more_first[e][i]);
          ce = ce0 + a * take(s.dc_more[e][i]);
        }
    }
    // The summation-density scheme predicts the density at the end of the step: d = x0 +
    // dt u_h - x_h, as advance<2>() will apply it (pass_context.hpp), written here where x0 is
    // at hand rather than recovered in the next density pass. Walls keep their 0 of stage 1.
    if constexpr (S::summation_density && Stage == 1) {
      next_dx_[i] = static_cast<float>(x0 + dt * s.vx[i] - s.x[i]);
      next_dy_[i] = static_cast<float>(y0 + dt * s.vy[i] - s.y[i]);
    }
    // Counted once, at stage 2, which reads the rates of both stages.
    if constexpr (Stage == 2) bad += nonfinite > 0 ? 1 : 0;
  }
  bad_rates_ += bad;
}

template <class S, bool Ale, bool Split, bool Net>
bool SphSolver::step_impl(double dt) {
  if constexpr (S::shifting) {
    phys_.set_step(case_, dt);
  }
  // The inlet value of a feed that varies: its mean over the step, so that the buffer injects
  // the feed's amount whatever the step (second order in time for a smooth feed, like the
  // value at mid-step). The mid-step value held a pulse for a whole number of steps: at
  // dt = 1.875 ms a 50 ms pulse lasted 27 steps, 1.25% too much tracer. A constant feed is the
  // buffer's initial value.
  apply_feed(t_, dt);
  // Transport: explicit midpoint. Stage 1 predicts the density at x + dt/2 u (x0 = x then),
  // stage 2 at x0 + dt u*.
  bad_rates_ = 0;
  evaluate_impl<S, Ale, Split, Net>(0.5 * dt);
  density_predicted_ = S::summation_density && predict_density_;
  advance<S, 1, Net>(dt);
  store_.keep_first_stage_rates();
  evaluate_impl<S, Ale, Split, Net>(kWrittenByFirstStage);
  density_predicted_ = S::summation_density && predict_density_;
  // With the buffers, per species, for the ledger once the step is kept.
  std::array<double, Case::kMaxSpecies> exchange{};
  if (!Split && track_balance_)  // (sub-cycled diffusion accounts for its own exchange)
    for (int e = 0; e < case_.species_count(); ++e)
      exchange[static_cast<std::size_t>(e)] =
          dt * species_buffer_exchange_rate(store_, {kernel_, list_, phys_},
                                            store_.concentration(e).data(), case_.species_at(e).D);
  advance<S, 2, Net>(dt);
  if constexpr (Split) exchange = diffuse_species(dt);
  // Guards before anything outside the particle state changes: a failed step restores the
  // start state and leaves kinds, inflow rows, ledger and time as they were.
  if (!check_state(dt)) return false;
  for (int e = 0; e < Case::kMaxSpecies; ++e)
    ledgers_[static_cast<std::size_t>(e)].buffer_exchange += exchange[static_cast<std::size_t>(e)];
  react(dt);
  update_buffers(dt);
  t_ += dt;
  ++steps_;
  particle_steps_ += static_cast<double>(store_.size());
  if (needs_rebuild()) rebuild();
  return report_lost();
}

std::array<double, Case::kMaxSpecies> SphSolver::diffuse_species(double dt) {
  ScopedPhase timer(timers_, Phase::species);
  // Stages from this step's size (a final short step needs fewer).
  const auto plan = DiffusionSubcycler::plan(dt / limits_.diffusion);
  return subcycler_.advance(store_, {kernel_, list_, phys_}, dt, plan, track_balance_);
}

void SphSolver::react(double dt) {
  if (case_.species_count() > 1) return react_network(dt);
  // A case without reaction skips the pass (a factor of 1 changes nothing).
  const bool uniform = case_.species.k > 0.0;
  if (!uniform && case_.reactions.empty()) return;
  ScopedPhase timer(timers_, Phase::integration);
  const std::size_t n = store_.size();
  const double mass = store_.mass;
  // First-order reaction, exact over the step: it commutes with the linear transport
  // operators because k is uniform (docs/benchmark.md, section 6).
  const double decay = uniform ? species_decay(case_.species.k, dt) : 1.0;
  const std::span<const Reaction> tables = case_.reactions;
  double consumed = 0.0;
  // One pass: each particle takes the uniform decay, then the [[reaction]] tables, each exact
  // over the step at the particle's position, one after the other
  // (species/reaction_kinetics.hpp). Rates that are not linear in C, or not uniform in space,
  // do not commute with transport: this split (Lie) is first order in dt, an error of order
  // dt k (the steps are ~1e-5 s: ~1e-5 relative at k ~ 1/s).
#pragma omp parallel for schedule(static) reduction(+ : consumed)
  for (std::size_t i = 0; i < n; ++i) {
    if (store_.kind[i] != kFluidByte) continue;
    const double c_before = store_.c[i];
    double c = c_before * decay;  // exact: decay is 1 without species.k
    for (const Reaction& r : tables) {
      const double k_eff = r.zones.empty() ? r.k : r.k * zone_factor(r, store_.x[i], store_.y[i]);
      c = react_exact(r, k_eff, c, dt);
    }
    store_.c[i] = c;
    consumed += mass / store_.rho[i] * (c_before - c);
  }
  ledgers_[0].reaction += consumed;
}

void SphSolver::react_network(double dt) {
  if (case_.reactions.empty() && !(case_.species.k > 0.0)) return;
  ScopedPhase timer(timers_, Phase::integration);
  const std::size_t n = store_.size();
  const int count = case_.species_count();
  const double mass = store_.mass;
  // Net consumption per species (negative for a product).
  double consumed[Case::kMaxSpecies] = {};
  // Each particle is a batch reactor over the step (species/reaction_kinetics.hpp), split
  // from the transport as react() is.
#pragma omp parallel for schedule(static) reduction(+ : consumed[:Case::kMaxSpecies])
  for (std::size_t i = 0; i < n; ++i) {
    if (store_.kind[i] != kFluidByte) continue;
    std::array<double, Case::kMaxSpecies> conc{};
    conc[0] = store_.c[i];
    for (int e = 1; e < count; ++e) conc[e] = store_.c_more[e - 1][i];
    const std::array<double, Case::kMaxSpecies> before = conc;
    adrsph::react_network(case_, store_.x[i], store_.y[i],
                          std::span(conc).first(static_cast<std::size_t>(count)), dt);
    const double vol = mass / store_.rho[i];
    for (int e = 0; e < count; ++e) consumed[e] += vol * (before[e] - conc[e]);
    store_.c[i] = conc[0];
    for (int e = 1; e < count; ++e) store_.c_more[e - 1][i] = conc[e];
  }
  for (int e = 0; e < count; ++e) ledgers_[static_cast<std::size_t>(e)].reaction += consumed[e];
}

void SphSolver::apply_feed(double t, double dt) {
  for (int sp = 0; sp < case_.species_count(); ++sp) {
    const Case::Species& species = case_.species_at(sp);
    if (!feed_varies(species)) continue;
    ScopedPhase timer(timers_, Phase::boundaries);
    const double c_in =
        dt > 0.0 ? feed_integral(species, t, t + dt) / dt : inlet_concentration(species, t);
    scene_.set_inlet_concentration(sp, c_in);
    std::vector<double>& c = store_.concentration(sp);
    const std::size_t n = store_.size();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
      if (store_.kind[i] == kInletByte) c[i] = c_in;
  }
}

void SphSolver::update_buffers(double dt) {
  ScopedPhase timer(timers_, Phase::boundaries);
  scene_.advance_inflow(dt);
  const auto crossed = scene_.update_kinds(store_);
  crossings_.entered += crossed.entered;
  crossings_.left += crossed.left;
  for (std::size_t e = 0; e < ledgers_.size(); ++e) {
    ledgers_[e].inflow += crossed.species_in[e];
    ledgers_[e].outflow += crossed.species_out[e];
  }
}

bool SphSolver::step(double dt) {
  if (released_) throw std::logic_error("SphSolver::step after release_stepping_memory()");
  return (this->*step_fn_)(dt);
}

void SphSolver::release_stepping_memory() {
  released_ = true;
  for (auto* v : {&next_dx_, &next_dy_}) std::vector<float>().swap(*v);
  density_predicted_ = false;
  list_.release();
  pair_records_.release();
  (void)monitor_.release_storage();
  subcycler_.release();
  trim_heap();
}

void SphSolver::shed_for_output() {
  pair_records_.release();
  trim_heap();
}

void SphSolver::trim_heap() {
#ifdef __GLIBC__
  // Freed blocks below the top of the heap stay resident until trimmed.
  malloc_trim(0);
#endif
}

FieldFrame SphSolver::frame(std::vector<double>& pressure_pa) const {
  const std::size_t n = store_.size();
  pressure_pa.resize(n);
  // Internal pressure unit: kg/m^3 * mm^2/s^2 = 1e-6 Pa.
  for (std::size_t i = 0; i < n; ++i) pressure_pa[i] = store_.p[i] * 1e-6;
  FieldFrame f;
  f.t = t_;
  f.step = steps_;
  f.x = std::span(store_.x).first(n);
  f.y = std::span(store_.y).first(n);
  f.vx = std::span(store_.vx).first(n);
  f.vy = std::span(store_.vy).first(n);
  f.rho = std::span(store_.rho).first(n);
  f.p = pressure_pa;
  f.c = std::span(store_.c).first(n);
  f.kind = std::span(store_.kind).first(n);
  for (int e = 0; e < store_.needs().more_species; ++e)
    f.more_c.emplace_back("c_" + case_.more_species[e].name, std::span(store_.c_more[e]).first(n));
  return f;
}

}  // namespace adrsph
