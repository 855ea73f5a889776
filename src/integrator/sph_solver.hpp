// The SPH solver: owns the particles, the neighbour structures and the scene, and advances
// the state by explicit midpoint steps (two evaluations per step).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "adrsph/case.hpp"
#include "adrsph/checkpoint.hpp"
#include "adrsph/simulation.hpp"
#include "analysis/probes_sph.hpp"
#include "boundaries/channel_scene.hpp"
#include "case/failure_advice.hpp"
#include "integrator/phase_timers.hpp"
#include "neighbours/cell_grid.hpp"
#include "neighbours/displacement_monitor.hpp"
#include "neighbours/neighbour_list.hpp"
#include "particles/particle_store.hpp"
#include "schemes/pair_records.hpp"
#include "schemes/pass_context.hpp"
#include "species/diffusion_subcycling.hpp"

namespace adrsph {

// Species bookkeeping over the run (moles per unit depth, V C summed), for the balance
// inflow - outflow + diffusive exchange - reaction = change of the fluid inventory.
struct SpeciesLedger {
  double inflow = 0.0, outflow = 0.0;  // carried by particles crossing x = 0 and x = L
  double buffer_exchange = 0.0;        // diffused from the inflow/outflow buffers (if tracked)
  double reaction = 0.0;               // consumed by the reaction
};

class SphSolver {
 public:
  explicit SphSolver(const Case& c);
  // Start from the concentration `initial_c` instead of c_init: one value per initial particle
  // in ChannelScene::for_each_initial() order (time.warm_start).
  SphSolver(const Case& c, std::span<const double> initial_c);

  // One explicit midpoint step of size dt. Returns false when a guard trips; failure() then
  // says why and what to change. A guard on the state (non-finite values, speed, density, C
  // band) undoes the step: particles, kinds, inflow rows, ledger and time are as before it.
  // Particles found outside the channel at the re-sort after a step are removed with it: that
  // step is kept, and the run is meant to stop there.
  bool step(double dt);

  double time() const { return t_; }
  long steps() const { return steps_; }
  const TimeStepLimits& dt_limits() const { return limits_; }
  // What the passes are given (benchmarks time single passes with them).
  const PhysicsConstants& physics() const { return phys_; }
  const QuinticKernel& kernel() const { return kernel_; }
  const CellGrid& grid() const { return grid_; }
  double cutoff() const { return cutoff_; }
  // The rule the lists are built with: a wall's row lists no walls (only the boundary pass
  // reads it, and it samples the fluid side alone); a prescribed flow has no boundary pass,
  // and its walls' rows are empty. Walls never change kind, so no row goes stale between builds.
  NeighbourList::Omit wall_rows() const {
    return {store_.kind.data(), kWallByte, case_.flow == Flow::prescribed};
  }
  const ParticleStore& particles() const { return store_; }
  ParticleStore& particles() { return store_; }
  PhaseTimers& timers() { return timers_; }
  // What happened at the last failed step (no advice: failure_advice() in src/case says what
  // to change in the case), and its kind.
  const std::string& failure() const { return failure_; }
  FailureKind failure_kind() const { return failure_site_.kind; }
  // Where: the time and step of the failed step, the particle that failed worst (its last
  // good position; NaN for lost particles, which are removed) and the value that tripped
  // the guard (speed, |rho / rho0 - 1|, distance of C outside its band, particles lost).
  struct FailureSite {
    FailureKind kind = FailureKind::none;
    double t = 0.0;
    long step = 0;
    double x = std::numeric_limits<double>::quiet_NaN();
    double y = std::numeric_limits<double>::quiet_NaN();
    double value = 0.0;
  };
  const FailureSite& failure_site() const { return failure_site_; }
  long lost_particles() const { return lost_; }
  // Particles that crossed the inlet and outlet planes since the start (the species they
  // carried is in the ledger: inflow, outflow).
  struct Crossings {
    long entered = 0, left = 0;
  };
  const Crossings& boundary_crossings() const { return crossings_; }
  // Track the diffusive exchange with the buffers (one extra neighbour pass per step).
  void track_species_balance(bool on) { track_balance_ = on; }
  // Of species `species` (0: the first, 1..: the network's others, Case::species_at).
  const SpeciesLedger& species_ledger(int species = 0) const {
    return ledgers_[static_cast<std::size_t>(species)];
  }
  // Moles of species `species` carried by the fluid particles: sum V C with V = m / rho.
  double species_inventory(int species = 0) const;
  std::size_t fluid_count() const;
  double mean_neighbours() const { return list_.mean_neighbours(); }
  long list_rebuilds() const { return rebuilds_; }
  // Of those, the builds that took two passes over the candidates (NeighbourList::one_pass()).
  long list_two_pass_builds() const { return two_pass_builds_; }
  double particle_steps() const { return particle_steps_; }
  // Heap bytes of the particle arrays, the neighbour lists, the diffusion weights and the force
  // pass's neighbour records (pair_records.hpp).
  std::size_t particle_bytes() const { return store_.bytes(); }
  std::size_t list_bytes() const { return list_.bytes(); }
  std::size_t diffusion_weight_bytes() const { return subcycler_.bytes(); }
  std::size_t pair_record_bytes() const { return pair_records_.bytes(); }
  // Probe sampling on the grid of the last sort, read-only: a particle within the support of
  // a probe now was within support + moved_abs_ at the sort, so the search covers that many
  // cells of size cutoff_ around it.
  // `species`: which species it samples (Case::species_at order).
  ProbeSampler sampler(int species = 0) const {
    const int rings = std::max(
        1, static_cast<int>(std::ceil((kernel_.support + moved_abs_) / cutoff_ * (1.0 + 1e-12))));
    const double* c = store_.concentration(species).data();
    return ProbeSampler{store_, grid_, kernel_, rings, c};
  }
  int species_count() const { return 1 + store_.needs().more_species; }
  FieldFrame frame(std::vector<double>& pressure_pa) const;
  // The end of a run: give back what only stepping needs (neighbour lists, diffusion
  // weights, predicted displacements and densities), so that writing the final frame and
  // files does not add HDF5's code and buffers on top of them (perf/README.md, 3.14). The
  // state, the probes' sampler and frame() stay valid; step() refuses afterwards.
  void release_stepping_memory();
  // Before a frame or a checkpoint is written mid-run: give back what the next pass makes
  // anew anyway, so that HDF5's code and buffers take its place instead of adding to the
  // run's peak memory (perf/README.md, 3.21): the pair records, which every pass fills anew.
  // The run's numbers do not change.
  void shed_for_output();
  // Recompute the derived fields (density, pressure) and rates of the current state
  // without advancing: used by tests and benchmarks.
  void evaluate();
  // Conventional scheme: take the next summation density in the force pass (default) or in
  // a pass of its own (for A/B tests and benchmarks; the numbers are the same).
  void predict_density(bool on) { predict_density_ = on; }
  // Re-sort, feed/drain the buffers and rebuild the neighbour lists.
  void rebuild();

  // Checkpoint/restart (adrsph/checkpoint.hpp). A snapshot is exact only when taken right
  // after a rebuild (just_rebuilt()): restore() rebuilds the lists from the positions.
  bool just_rebuilt() const { return moved_abs_ == 0.0; }
  SolverSnapshot snapshot() const;
  // Replace the state by a snapshot of a solver of the same case. Throws
  // std::invalid_argument when it does not fit the case.
  void restore(const SolverSnapshot& s);

 private:
  // Net: a network of several species (interaction_pass.hpp, Network).
  template <class S, bool Ale, bool Split, bool Net>
  bool step_impl(double dt);
  // The displacement the summation-density scheme predicts the density for (pass_context.hpp):
  // a_next >= 0: the first stage's, a_next u (a_next = dt/2); a_next < 0: none (0); NaN: the
  // second stage's, written by advance<S, 1> (which has the start of the step at hand).
  template <class S, bool Ale, bool Split, bool Net>
  void evaluate_impl(double a_next);
  template <class S, bool Ale, bool Split, bool Net>
  void evaluate_at_rest() {  // evaluate() (a prediction for the current positions, unused)
    evaluate_impl<S, Ale, Split, Net>(-1.0);
  }
  template <class S, bool Ale, bool Net>
  void bind(bool split);
  // The update of stage 1 or 2 of the explicit midpoint step of size dt (midpoint.hpp).
  template <class S, int Stage, bool Net>
  void advance(double dt);
  bool check_state(double dt);
  // A failed step of size dt: every particle back to its start state (midpoint.hpp).
  void undo_step(double dt);
  long bad_rates_ = 0;  // fluid particles with a non-finite rate this step (taken as zero)
  // The phases of a step after the transport (step_impl reads as this list).
  // Sub-cycled diffusion; returns the buffer exchange of each species.
  std::array<double, Case::kMaxSpecies> diffuse_species(double dt);
  void react(double dt);
  void react_network(double dt);   // react() for several species
  void update_buffers(double dt);  // inflow rows, kinds, crossings
  // A feed that varies in time (species/inlet_feed.hpp): the inflow buffer and the rows fed
  // from now on carry the feed's mean over [t, t + dt] (its value at t when dt = 0).
  void apply_feed(double t, double dt);
  bool report_lost();
  // The conventional scheme's summation density at the positions of the next evaluation is
  // taken by the force pass (pass_context.hpp) into the store's predicted_density, which a
  // re-sort carries along. It is valid (density_predicted_) from one evaluation to the next of
  // a step that goes on, not after a step is undone or a snapshot restored.
  std::vector<float> next_dx_, next_dy_;  // displacement of the coming stage (walls 0)
  bool density_predicted_ = false;
  bool predict_density_ = true;
  bool released_ = false;  // release_stepping_memory() was called

  Case case_;
  ChannelScene scene_;
  QuinticKernel kernel_;
  PhysicsConstants phys_;
  TimeStepLimits limits_;
  ParticleStore store_;
  CellGrid grid_;
  NeighbourList list_;
  PairRecords pair_records_;  // what the force pass reads of each neighbour, per evaluation
  PhaseTimers timers_;
  bool (SphSolver::*step_fn_)(double) = nullptr;
  void (SphSolver::*eval_fn_)() = nullptr;
  // Re-sort / list rebuild criterion. moved_abs_ bounds how far any particle moved since the
  // last build (the inflow buffer must be re-fed before its upstream gap reaches the fluid's
  // support; the probe search widens with it, sampler()). Once 2 moved_abs_ > skin, the monitor
  // bounds the relative displacement of possible pairs (displacement_monitor.hpp).
  bool needs_rebuild();
  void trim_heap();  // give freed heap pages back to the system (glibc)
  DisplacementMonitor monitor_;
  long rebuilds_ = 0;
  long two_pass_builds_ = 0;
  double cutoff_ = 0.0, skin_ = 0.0, moved_abs_ = 0.0;
  double abs_limit_ = 0.0;  // absolute displacement allowed between re-sorts
  double t_ = 0.0;
  long steps_ = 0;
  long lost_ = 0;
  long lost_reported_ = 0;  // lost_ at the last failure report
  Crossings crossings_;
  std::array<SpeciesLedger, Case::kMaxSpecies> ledgers_{};  // per species
  DiffusionSubcycler subcycler_;
  bool track_balance_ = false;
  double particle_steps_ = 0.0;
  std::string failure_;
  FailureSite failure_site_;
};

}  // namespace adrsph
