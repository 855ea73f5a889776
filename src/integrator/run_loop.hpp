// The stepping loop of a run, one loop for its two uses:
//   Mode::run         the run itself: steps the solver to t_end (or steady state, or
//                     time.max_steps), samples the probes at check instants, feeds the
//                     steady-state detector, reports progress, keeps the averaging window and
//                     the history, hands field frames to the observer and takes checkpoints
//                     when it asks (adrsph/checkpoint.hpp);
//   Mode::warm_start  the prescribed-flow run of time.warm_start: the same steps, checks and
//                     steady test, but no progress, fields, averaging or history, and no
//                     checkpoints: a stop request ends it as interrupted (its state is not
//                     worth a checkpoint yet), and it always stops when steady.
// Mode::run also samples the outlet every output.outlet_interval (outlet.csv), at the first
// step that reaches each multiple of it: the row holds the time it was taken.
#pragma once

#include <deque>
#include <random>
#include <utility>
#include <vector>

#include "adrsph/case.hpp"
#include "adrsph/simulation.hpp"
#include "analysis/steady_state.hpp"

namespace adrsph {

class SphSolver;

// Probe-line samples per section average: 4 per particle spacing across the channel, >= 20.
int section_samples(const Case& c);
// The section averages at the stations (station_x_positions) from the probe-line samples.
StationTable stations_from(const ProbeTable& p, double length);
// The probe table of a network (RunLoop::sample: the species one after the other) split into
// one table per species.
std::vector<ProbeTable> split_species(const ProbeTable& all, int count);
// The outlet series of a network (RunLoop::sample_outlet: one row per species at each
// sample) split into one series per species.
std::vector<std::vector<OutletRow>> split_outlet(const std::vector<OutletRow>& all, int count);
// Peak resident memory of the process so far [bytes].
double peak_rss_bytes();

class RunLoop {
 public:
  enum class Mode { run, warm_start };
  enum class End { finished, steady, failed, interrupted };  // finished: t_end or max_steps

  // `wall_start`: omp_get_wtime() when the run began (before its set-up); `result` receives
  // the history (Mode::run) and lends the checkpoint its run-level fields; `resume` restores
  // the loop's own state (detector, window, check instants, fields written).
  RunLoop(const Case& c, SphSolver& solver, RunObserver& observer, Mode mode, RunResult& result,
          double wall_start, const RunCheckpoint* resume = nullptr);

  End run();

  // Sample the probe lines now (into last_probes(), and the averaging window in Mode::run).
  void sample();
  void emit_fields();
  const ProbeTable& last_probes() const { return last_probes_; }
  const std::deque<std::pair<double, ProbeTable>>& window() const { return window_; }
  const SteadyStateDetector& steady() const { return steady_; }
  // Wall seconds of the run so far and of its stepping alone (earlier segments included).
  double wall_now() const;
  double stepping_now() const;

 private:
  double next_interval();
  // The outlet row of outlet.csv now (Mode::run with output.outlet_interval > 0), and the
  // next sample instant: the next whole multiple of the interval.
  void sample_outlet();
  void report_progress(double change);
  void checkpoint();

  const Case& c_;
  SphSolver& solver_;
  RunObserver& observer_;
  Mode mode_;
  RunResult& result_;
  SteadyStateDetector steady_;
  std::deque<std::pair<double, ProbeTable>> window_;
  ProbeTable last_probes_;
  std::vector<double> field_times_;
  std::size_t next_field_ = 0;
  // Check instants are jittered within +-50% of the interval in Mode::run (fixed seed: runs
  // repeat exactly): at regular instants the rows of particles passing the probes alias into
  // slow beats that look like drift; at irregular ones they become noise the detector can
  // measure.
  std::minstd_rand jitter_{12345};
  double next_check_ = 0.0;
  bool outlet_on_ = false;
  double next_outlet_ = 0.0;
  double dt_ = 0.0, eps_t_ = 0.0;
  int n_section_ = 0;
  long first_step_ = 0;  // solver steps when this segment began (progress rate)
  double wall_start_ = 0.0, wall_steps_start_ = 0.0;
  double wall_before_ = 0.0, stepping_before_ = 0.0;  // earlier segments of a continued run
};

}  // namespace adrsph
