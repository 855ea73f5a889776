// The run loop: steps the solver to t_end (or steady state, or max_steps), samples the
// probes, detects steady state, reports progress, hands field frames to the observer, and
// takes checkpoints when the observer asks (checkpoint/restart: adrsph/checkpoint.hpp).
#include <omp.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <random>
#include <sstream>

#include "adrsph/simulation.hpp"
#include "analysis/steady_state.hpp"
#include "boundaries/channel_scene.hpp"
#include "case/failure_advice.hpp"
#include "integrator/sph_solver.hpp"

namespace adrsph {

namespace {

// Mean of the probe tables in the averaging window.
ProbeTable average(const std::deque<std::pair<double, ProbeTable>>& window) {
  ProbeTable mean = window.front().second;
  auto accumulate = [](std::vector<double>& acc, const std::vector<double>& v) {
    for (std::size_t i = 0; i < acc.size(); ++i) acc[i] += v[i];
  };
  for (std::size_t k = 1; k < window.size(); ++k) {
    accumulate(mean.c_y0, window[k].second.c_y0);
    accumulate(mean.c_yp25, window[k].second.c_yp25);
    accumulate(mean.c_ym25, window[k].second.c_ym25);
    accumulate(mean.c_mean, window[k].second.c_mean);
  }
  const double inv = 1.0 / static_cast<double>(window.size());
  for (auto* v : {&mean.c_y0, &mean.c_yp25, &mean.c_ym25, &mean.c_mean})
    for (double& x : *v) x *= inv;
  return mean;
}

StationTable stations_from(const ProbeTable& p, double length) {
  StationTable s;
  s.x_mm = station_x_positions(length);
  for (double xs : s.x_mm) {
    std::size_t best = 0;
    for (std::size_t i = 0; i < p.x_mm.size(); ++i)
      if (std::fabs(p.x_mm[i] - xs) < std::fabs(p.x_mm[best] - xs)) best = i;
    s.c_mean.push_back(p.c_mean[best]);
  }
  return s;
}

double peak_rss_bytes() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return 1024.0 * static_cast<double>(ru.ru_maxrss);  // Linux reports KiB
}

int section_samples(const Case& c) {
  return std::max(20, static_cast<int>(std::lround(4.0 * c.geometry.half_width / c.particles.dx)));
}

// time.warm_start: solve the species in the prescribed (analytic) flow to steady state, which
// costs little (no momentum, no acoustic step), and hand its C field to the full run: the
// WCSPH run then starts near its own steady state instead of from C = c_init. The steady
// criterion of the full run still counts from its own t = 0 (steady_state.hpp), so the start
// cannot shorten the time the WCSPH flow needs to sweep its slow streamlines.
// Returns the initial C of every particle (ChannelScene::for_each_initial order). The
// prescribed-flow solver is gone before the full run's solver is built: one solver in memory.
std::vector<double> warm_start(const Case& c, RunObserver& observer, RunResult& result) {
  const double wall0 = omp_get_wtime();
  Case pre = c;
  pre.flow = Flow::prescribed;
  pre.time.cfl = std::max(c.time.cfl, 1.0);  // advective limit: particles move <= h per step
  pre.time.dt = 0.0;
  pre.time.dt_factor = 0.0;  // a stability study's fixed step is for the WCSPH run only
  // Steps of up to h make the lists age fast: a larger skin pays (perf/README.md, 3.4).
  pre.particles.skin = std::max(c.particles.skin, Case::Particles::kPrescribedSkin);
  SphSolver solver(pre);
  const double dt = solver.dt_limits().chosen;
  SteadyStateDetector steady(steady_criterion(pre));
  const int n_section = section_samples(c);
  double next_check = c.time.check_interval;
  while (solver.time() < c.time.t_end && !steady.steady()) {
    if (!solver.step(std::min(dt, c.time.t_end - solver.time())))
      throw WarmStartFailed(
          "the warm start (species in the prescribed flow) failed: " + solver.failure() + " " +
          failure_advice(solver.failure_kind(), pre, 0.0) + " Or set time.warm_start = false.");
    if (observer.checkpoint_request(omp_get_wtime() - wall0) == CheckpointRequest::write_and_stop)
      throw RunInterrupted("interrupted during the warm start (no checkpoint yet)");
    if (solver.time() >= next_check) {
      next_check += c.time.check_interval;
      steady.update(solver.time(), solver.sampler().probe_lines(c.geometry.length,
                                                                c.geometry.half_width, n_section));
    }
  }
  const ProbeSampler from = solver.sampler();
  std::vector<double> x, y, field;
  std::vector<Kind> kind;
  ChannelScene(c).for_each_initial([&](double px, double py, Kind k) {
    x.push_back(px);
    y.push_back(py);
    kind.push_back(k);
  });
  field.resize(x.size());
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < x.size(); ++i) {
    switch (kind[i]) {
      case Kind::fluid:
      case Kind::outlet:
        field[i] = from.concentration_at(x[i], y[i]);
        break;
      case Kind::inlet:
        field[i] = c.species.c_in;
        break;
      default:
        field[i] = 0.0;
        break;  // walls carry no species
    }
  }
  result.warm_started = true;
  result.warm_start_t = solver.time();
  result.warm_start_steps = solver.steps();
  result.warm_start_steady = steady.steady();
  result.warm_start_wall_s = omp_get_wtime() - wall0;
  return field;
}

// The solver of a new run (with its warm start), or of a continued one.
SphSolver make_solver(const Case& c, RunObserver& observer, RunResult& result,
                      const RunCheckpoint* resume) {
  if (resume) {
    SphSolver solver(c);
    solver.restore(resume->solver);
    return solver;
  }
  if (c.time.warm_start && c.flow == Flow::wcsph)
    return SphSolver(c, warm_start(c, observer, result));
  return SphSolver(c);
}

}  // namespace

RunResult run_simulation(const Case& c, RunObserver& observer, const RunCheckpoint* resume) {
  RunResult result;
  const double wall_start = omp_get_wtime();
  double wall_before = 0.0, stepping_before = 0.0;  // earlier segments of a continued run
  if (resume) {
    wall_before = resume->wall_s;
    stepping_before = resume->stepping_wall_s;
    result.restarts = resume->restarts + 1;
    result.peak_rss_bytes = resume->peak_rss_bytes;
    result.warm_started = resume->warm_started;
    result.warm_start_steady = resume->warm_start_steady;
    result.warm_start_t = resume->warm_start_t;
    result.warm_start_steps = resume->warm_start_steps;
    result.warm_start_wall_s = resume->warm_start_wall_s;
    result.history = resume->history;
  }
  SphSolver solver = make_solver(c, observer, result, resume);
  const double wall_steps_start = omp_get_wtime();
  auto wall_now = [&] { return wall_before + omp_get_wtime() - wall_start; };
  auto stepping_now = [&] { return stepping_before + omp_get_wtime() - wall_steps_start; };
  result.dt = solver.dt_limits();
  const double dt = result.dt.chosen;
  const double length = c.geometry.length, half_width = c.geometry.half_width;
  const int n_section = section_samples(c);
  result.probe_interpolation = probe_interpolation_text(n_section);

  SteadyStateDetector steady(steady_criterion(c));
  result.steady_criterion = {steady.criterion().tol, steady.criterion().window,
                             steady.criterion().t_min};
  std::deque<std::pair<double, ProbeTable>> window;
  std::vector<double> field_times = c.output.field_times;
  std::sort(field_times.begin(), field_times.end());
  std::size_t next_field = 0;
  std::vector<double> pressure_pa;
  // Check instants are jittered within +-50% of the interval (fixed seed: runs repeat
  // exactly): at regular instants the rows of particles passing the probes alias into slow
  // beats that look like drift; at irregular ones they become noise the detector can measure.
  std::minstd_rand jitter(12345);
  auto next_interval = [&] {
    return c.time.check_interval * (0.5 + std::uniform_real_distribution<double>(0.0, 1.0)(jitter));
  };
  double next_check = 0.0;
  if (resume) {
    steady.restore(resume->steady);
    window.assign(resume->average_window.begin(), resume->average_window.end());
    std::istringstream(resume->jitter_state) >> jitter;
    next_check = resume->next_check;
    next_field = resume->next_field;
  } else {
    next_check = next_interval();
  }
  ProbeTable last_probes;
  const double eps_t = 1e-9 * dt;

  auto emit_fields = [&] {
    ScopedPhase timer(solver.timers(), Phase::output);
    observer.on_fields(solver.frame(pressure_pa));
  };
  auto sample = [&] {
    ScopedPhase timer(solver.timers(), Phase::probes);
    last_probes = solver.sampler().probe_lines(length, half_width, n_section);
    if (c.time.average_window > 0) {
      window.emplace_back(solver.time(), last_probes);
      while (window.front().first < solver.time() - c.time.average_window - eps_t)
        window.pop_front();
    }
  };
  auto checkpoint = [&] {
    ScopedPhase timer(solver.timers(), Phase::output);
    RunCheckpoint cp;
    cp.solver = solver.snapshot();
    cp.steady = steady.snapshot();
    cp.average_window.assign(window.begin(), window.end());
    cp.history = result.history;
    std::ostringstream js;
    js << jitter;
    cp.jitter_state = js.str();
    cp.next_check = next_check;
    cp.next_field = next_field;
    cp.wall_s = wall_now();
    cp.stepping_wall_s = stepping_now();
    cp.peak_rss_bytes = std::max(result.peak_rss_bytes, peak_rss_bytes());
    cp.restarts = result.restarts;
    cp.warm_started = result.warm_started;
    cp.warm_start_steady = result.warm_start_steady;
    cp.warm_start_t = result.warm_start_t;
    cp.warm_start_steps = result.warm_start_steps;
    cp.warm_start_wall_s = result.warm_start_wall_s;
    observer.on_checkpoint(cp);
  };

  bool ok = true, interrupted = false;
  CheckpointRequest pending = CheckpointRequest::none;
  while (solver.time() < c.time.t_end - eps_t &&
         (c.time.max_steps == 0 || solver.steps() < c.time.max_steps)) {
    const double h = std::min(dt, c.time.t_end - solver.time());
    if (!solver.step(h)) {
      ok = false;
      break;
    }
    const double t = solver.time();
    if (t >= next_check - eps_t) {
      next_check += next_interval();
      sample();
      Progress pr;
      pr.t = t;
      pr.t_end = c.time.t_end;
      pr.step = solver.steps();
      pr.wall_s = wall_now();
      pr.steps_per_s = (pr.step - (resume ? resume->solver.steps : 0)) /
                       std::max(omp_get_wtime() - wall_start, 1e-9);
      pr.eta_s = (c.time.t_end - t) / dt / std::max(pr.steps_per_s, 1e-9);
      const double t_min = steady.criterion().t_min;
      if (c.time.stop_when_steady && t < t_min && t_min < c.time.t_end)
        pr.eta_steady_s = (t_min - t) / dt / std::max(pr.steps_per_s, 1e-9);
      pr.steady_change = steady.update(t, last_probes);
      result.history.push_back({t, stations_from(last_probes, length).c_mean, pr.steady_change});
      observer.on_progress(pr);
      if (steady.steady() && c.time.stop_when_steady) break;
    }
    while (next_field < field_times.size() && t >= field_times[next_field] - eps_t) {
      ++next_field;
      emit_fields();
    }
    if (pending == CheckpointRequest::none) pending = observer.checkpoint_request(wall_now());
    // Served at a rebuild, where the snapshot is exact (checkpoint.hpp).
    if (pending != CheckpointRequest::none && solver.just_rebuilt()) {
      checkpoint();
      if (pending == CheckpointRequest::write_and_stop) {
        interrupted = true;
        break;
      }
      pending = CheckpointRequest::none;
    }
  }

  result.t_reached = solver.time();
  result.steps = solver.steps();
  result.n_particles = solver.particles().size();
  result.n_fluid = solver.fluid_count();
  result.peak_rss_bytes = std::max(result.peak_rss_bytes, peak_rss_bytes());
  if (interrupted) {
    result.status = "interrupted";
    result.message =
        "stopped on request after a checkpoint at t = " + std::to_string(solver.time()) +
        " s; continue with adrsph run --restart";
    result.wall_s = wall_now();
    return result;
  }
  if (!ok) {
    result.status = "failed";
    const SphSolver::FailureSite& f = solver.failure_site();
    result.message = solver.failure() + " " +
                     failure_advice(f.kind, c, solver.dt_limits().acoustic, f.step == 1);
    result.failure = {failure_name(f.kind), f.t, f.step, f.x, f.y, f.value};
  }
  // Final probes: instantaneous, or the mean over the final window.
  if (c.time.average_window > 0 && !window.empty() && ok) {
    result.probes = average(window);
    result.average_window = window.back().first - window.front().first;
  } else {
    sample();
    result.probes = last_probes;
  }
  result.stations = stations_from(result.probes, length);
  emit_fields();

  result.wall_s = wall_now();
  // Throughput of the stepping alone (set-up and warm start excluded).
  result.particle_steps_per_s = solver.particle_steps() / std::max(stepping_now(), 1e-9);
  result.list_rebuilds = solver.list_rebuilds();
  result.mean_neighbours = solver.mean_neighbours();
  result.steady = steady.steady();
  result.t_steady = steady.t_steady();
  result.lost_particles = solver.lost_particles();
  result.phase_seconds = solver.timers().table();
  return result;
}

}  // namespace adrsph
