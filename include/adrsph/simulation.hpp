// One SPH simulation of a case, from t = 0 to t_end (or steady state, or max_steps).
// The CLI (`adrsph run`) drives it and owns all file output; the simulation reports
// through a RunObserver and returns a RunResult.
#pragma once

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "adrsph/case.hpp"
#include "adrsph/checkpoint.hpp"
#include "adrsph/probes.hpp"

namespace adrsph {

// Version of what a run computes (not of how fast): raised by every change that moves a
// run's numbers beyond round-off. run.json records it; `adrsph study` treats a done or
// interrupted run of another version as stale and runs it again, so that a study never
// mixes results of two engines. 1: up to the zero-flux outlet. 2: the outflow buffer takes
// no part in the species diffusion (the outlet station moved by up to 5% at Pe = 10).
inline constexpr int kResultsVersion = 2;

// Particle kinds as stored in the field output (`kind` dataset).
enum class Kind : std::uint8_t { fluid = 0, wall = 1, inlet = 2, outlet = 3 };
// The store keeps kinds as plain bytes (a SoA array the passes read): these are their values,
// one spelling for every pass.
inline constexpr auto kFluidByte = static_cast<std::uint8_t>(Kind::fluid);
inline constexpr auto kWallByte = static_cast<std::uint8_t>(Kind::wall);
inline constexpr auto kInletByte = static_cast<std::uint8_t>(Kind::inlet);
inline constexpr auto kOutletByte = static_cast<std::uint8_t>(Kind::outlet);

// A read-only view of the particle state at one instant (plain arrays, SoA).
struct FieldFrame {
  double t = 0.0;
  long step = 0;
  std::span<const double> x, y, vx, vy, rho, p, c;  // mm, mm/s, kg/m^3, Pa, mol/m^3
  std::span<const std::uint8_t> kind;               // values of Kind
  // The second and later species of a network: (dataset name "c_<species name>", values).
  std::vector<std::pair<std::string, std::span<const double>>> more_c;
};

struct Progress {
  double t = 0.0, t_end = 0.0;
  long step = 0;
  double wall_s = 0.0;
  double steps_per_s = 0.0;
  double eta_s = 0.0;          // estimated wall seconds to t_end
  double eta_steady_s = -1.0;  // to the earliest time the steady test may stop the run (-1: none)
  double steady_change = 0.0;  // last probe change measure (see time.steady_tol)
};

// What the observer asks of the run after a step (checkpoint/restart).
enum class CheckpointRequest {
  none,
  write,           // write a checkpoint and go on (periodic checkpoints)
  write_and_stop,  // write a checkpoint and end the run as "interrupted" (a signal)
};

class RunObserver {
 public:
  virtual ~RunObserver() = default;
  virtual void on_progress(const Progress&) {}
  // Called at each requested output time, at the end, and with the last good state on failure.
  virtual void on_fields(const FieldFrame&) {}
  // Asked after every step, with the wall time of the run so far. A request is served at the
  // next neighbour-list rebuild (every few tens of steps), where a snapshot is exact.
  virtual CheckpointRequest checkpoint_request(double /*wall_s*/) {
    return CheckpointRequest::none;
  }
  virtual void on_checkpoint(const RunCheckpoint&) {}
};

// Thrown when the observer asks to stop before the run has a state worth a checkpoint
// (during the warm start).
class RunInterrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The prescribed-flow run of time.warm_start failed a guard: there is no initial field to
// start the WCSPH run from (what() says why and what to change).
class WarmStartFailed : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct TimeStepLimits {
  double acoustic = 0.0, advective = 0.0, viscous = 0.0, diffusion = 0.0;  // 0: not applicable
  double chosen = 0.0;
  std::string binding;       // which limit set dt
  int diffusion_stages = 1;  // RKL2 diffusion stages (sparse products) per step; 1: not split
};

struct RunResult {
  std::string status = "ok";  // "ok" | "failed" | "interrupted" (checkpoint written)
  std::string message;        // why it failed, and what to change
  // When status is "failed": which guard tripped ("non_finite", "speed", "density",
  // "concentration", "lost_particles"), when, and where (the worst particle's last good
  // position, NaN when unknown) with the value that tripped it (run.json "failure").
  struct Failure {
    std::string kind;
    double t = 0.0;
    long step = 0;
    double x = 0.0, y = 0.0, value = 0.0;
  } failure;
  double t_reached = 0.0;
  long steps = 0;
  double wall_s = 0.0;
  std::size_t n_particles = 0;        // all particles (fluid + wall + buffers) at the end
  std::size_t n_fluid = 0;            // fluid particles at the end
  double particle_steps_per_s = 0.0;  // sum over steps of particles / wall time
  long list_rebuilds = 0;             // re-sorts + neighbour-list builds (set-up included)
  long list_two_pass_builds = 0;      // of those, builds in two passes over the candidates
  double mean_neighbours = 0.0;       // list entries per particle at the last build (skin incl.)
  TimeStepLimits dt;
  bool steady = false;
  double t_steady = 0.0;
  long lost_particles = 0;
  std::vector<std::pair<std::string, double>> phase_seconds;  // timer name -> seconds
  ProbeTable probes;                                          // of the first species
  StationTable stations;
  // The second and later species of a network, sampled as the first (probes_<name>.csv,
  // stations_<name>.csv).
  struct SpeciesProbes {
    std::string name;
    ProbeTable probes;
    StationTable stations;
  };
  std::vector<SpeciesProbes> more_species;
  double average_window =
      0.0;  // probes averaged over [t_reached - window, t_reached]; 0: instantaneous
  std::string probe_interpolation;  // how probes were computed (text for run.json)
  // time.warm_start: the prescribed-flow run that gave the initial C field.
  bool warm_started = false;
  double warm_start_t = 0.0;  // simulated time of the prescribed run
  long warm_start_steps = 0;
  double warm_start_wall_s = 0.0;  // included in wall_s
  bool warm_start_steady = false;
  // Section averages at the stations at every probe check: the approach to steady state.
  std::vector<HistoryRow> history;
  // The outlet every output.outlet_interval (outlet.csv; empty when the interval is 0), of
  // the first species; the others of a network in more_outlet (outlet_<name>.csv).
  std::vector<OutletRow> outlet;
  std::vector<std::vector<OutletRow>> more_outlet;
  double peak_rss_bytes = 0.0;  // largest resident set of the process (all segments)
  // Heap bytes the engine holds for the particles at the end (capacity): the particle arrays,
  // the neighbour lists, the diffusion weights of a split species step (0 if none), the force
  // pass's neighbour records (schemes/pair_records.hpp).
  struct {
    std::size_t particles = 0, neighbour_lists = 0, diffusion_weights = 0, pair_records = 0;
  } engine_bytes;
  int restarts = 0;  // times the run was continued from a checkpoint
  // Each species' ledger at the end (SphSolver::species_ledger: what particles carried
  // across x = 0 and x = L, what the reactions consumed) and what the fluid holds
  // (species_inventory), all divided by the nominal flow rate Q = 2R (2/3) u_max: amounts in
  // mol/m^3 s, comparable with a feed's int C_in dt. Counted since the start of the run's
  // WCSPH (or prescribed) solver: a warm start's prescribed run is not in it.
  struct SpeciesBalance {
    std::string name;
    double inflow = 0.0, outflow = 0.0, reacted = 0.0, held = 0.0;
  };
  std::vector<SpeciesBalance> species_balance;
  double balance_flow_rate = 0.0;  // Q [mm^2/s]
  struct {
    double tol = 0.0, window = 0.0, t_min = 0.0;  // the steady test used (steady_state.hpp)
  } steady_criterion;
};

// Runs the case. Numerical failures (NaN, blow-up, lost particles) do not throw: they end
// the run with status "failed" and a message, after on_fields() got the last good state.
// With `resume`, continue the run of that checkpoint (same case) instead of starting it.
RunResult run_simulation(const Case& c, RunObserver& observer,
                         const RunCheckpoint* resume = nullptr);

}  // namespace adrsph
