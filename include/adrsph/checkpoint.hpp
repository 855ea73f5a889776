// The state of a run between two steps, as plain data: what a checkpoint holds so that a
// run stopped and continued ends with exactly the result of one that was not.
//
// A checkpoint is taken right after the neighbour lists were rebuilt: the particles are then
// in cell order and the lists and the displacement monitor depend on the positions alone, so
// rebuilding them on restart gives the same lists, and the continued run repeats the
// uninterrupted one bit for bit (with the same number of threads: OpenMP reductions sum in
// an order that depends on it).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "adrsph/probes.hpp"

namespace adrsph {

// One particle array of a snapshot, by name. A solver's snapshot views the store's array
// (SphSolver::snapshot: valid until the solver steps on; the checkpoint is written from it
// without a copy, which would add a whole state's worth to a run's peak memory); an array
// read from a file, or any copy of a snapshot, owns its values.
template <class T>
class NamedArray {
 public:
  NamedArray(std::string array_name, std::span<const T> view)
      : name(std::move(array_name)), values_(view) {}
  NamedArray(std::string array_name, std::vector<T> data)
      : name(std::move(array_name)), owned_(std::move(data)), values_(owned_) {}
  NamedArray(const NamedArray& o)
      : name(o.name), owned_(o.values_.begin(), o.values_.end()), values_(owned_) {}
  NamedArray& operator=(const NamedArray& o) {
    if (this != &o) {
      name = o.name;
      owned_.assign(o.values_.begin(), o.values_.end());
      values_ = owned_;
    }
    return *this;
  }
  // A moved std::vector keeps its buffer, so the view of an owning array stays valid.
  NamedArray(NamedArray&&) noexcept = default;
  NamedArray& operator=(NamedArray&&) noexcept = default;
  ~NamedArray() = default;

  std::span<const T> values() const { return values_; }
  std::string name;

 private:
  std::vector<T> owned_;
  std::span<const T> values_;
};

// Particle arrays by name, in store order: the particle store's `state` fields (its field
// list, src/particles/particle_store.hpp: x, y, vx, vy, rho, c, kind, p and the optional ones
// of the run's scheme), so a new state field is checkpointed without an edit here or in the
// file format.
template <class T>
using NamedArrays = std::vector<NamedArray<T>>;
struct ParticleArrays {
  NamedArrays<double> f64;
  NamedArrays<float> f32;
  NamedArrays<std::uint8_t> u8;
  // The arrays of element type T (double, float or std::uint8_t).
  template <class T>
  NamedArrays<T>& of() {
    if constexpr (std::is_same_v<T, double>)
      return f64;
    else if constexpr (std::is_same_v<T, float>)
      return f32;
    else
      return u8;
  }
  template <class T>
  const NamedArrays<T>& of() const {
    return const_cast<ParticleArrays*>(this)->of<T>();
  }
};

// The solver: particle state (in store order) and every counter that the run reports.
struct SolverSnapshot {
  ParticleArrays particles;
  std::vector<double> inflow_row_tail;  // x of the most upstream inlet particle of each row
  double t = 0.0;
  long steps = 0, lost = 0, lost_reported = 0, rebuilds = 0, two_pass_builds = 0;
  double particle_steps = 0.0;
  // Per species (4 values each, up to 4 species): inflow, outflow, buffer exchange, reaction.
  // A checkpoint written before the ledger was kept per species holds the first 4 only.
  std::array<double, 16> ledger{};
  long entered = 0, left = 0;         // boundary crossings (their species: ledger)
  std::vector<double> phase_seconds;  // per PhaseTimers phase
};

// The steady-state detector: its samples and verdict.
struct SteadySnapshot {
  std::vector<double> t;                    // sample times
  std::vector<std::vector<double>> values;  // one flattened probe set per sample
  bool steady = false;
  double t_steady = 0.0;
};

// Everything of a run in progress.
struct RunCheckpoint {
  SolverSnapshot solver;
  SteadySnapshot steady;
  std::vector<std::pair<double, ProbeTable>> average_window;  // time.average_window samples
  std::vector<HistoryRow> history;
  std::vector<OutletRow> outlet;  // output.outlet_interval samples so far (every species')
  std::string jitter_state;       // the check-instant generator (std::minstd_rand, streamed)
  double next_check = 0.0;
  std::size_t next_field = 0;    // next output.field_times entry
  double wall_s = 0.0;           // wall time of the run so far (all segments)
  double stepping_wall_s = 0.0;  // of which stepping (throughput)
  double peak_rss_bytes = 0.0;   // largest peak RSS of the segments so far
  int restarts = 0;              // segments so far - 1
  // time.warm_start: the prescribed-flow start (see RunResult).
  bool warm_started = false, warm_start_steady = false;
  double warm_start_t = 0.0, warm_start_wall_s = 0.0;
  long warm_start_steps = 0;
  double t_start = 0.0;  // simulated time at which the steady test's clock starts
};

}  // namespace adrsph
