// The stepping loop of a run and of its warm start (run_loop.hpp).
#include "integrator/run_loop.hpp"

#include <omp.h>
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "integrator/sph_solver.hpp"

namespace adrsph {

int section_samples(const Case& c) {
  return std::max(20, static_cast<int>(std::lround(4.0 * c.geometry.half_width / c.particles.dx)));
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

std::vector<ProbeTable> split_species(const ProbeTable& all, int count) {
  const std::size_t n = all.x_mm.size() / static_cast<std::size_t>(count);
  std::vector<ProbeTable> parts(static_cast<std::size_t>(count));
  for (std::size_t s = 0; s < parts.size(); ++s) {
    const auto first = static_cast<std::ptrdiff_t>(s * n),
               last = first + static_cast<std::ptrdiff_t>(n);
    auto part = [&](const std::vector<double>& v) {
      return std::vector<double>(v.begin() + first, v.begin() + last);
    };
    parts[s] = {part(all.x_mm), part(all.c_y0), part(all.c_yp25), part(all.c_ym25),
                part(all.c_mean)};
  }
  return parts;
}

std::vector<std::vector<OutletRow>> split_outlet(const std::vector<OutletRow>& all, int count) {
  std::vector<std::vector<OutletRow>> parts(static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < all.size(); ++i) parts[i % parts.size()].push_back(all[i]);
  return parts;
}

double peak_rss_bytes() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return 1024.0 * static_cast<double>(ru.ru_maxrss);  // Linux reports KiB
}

RunLoop::RunLoop(const Case& c, SphSolver& solver, RunObserver& observer, Mode mode,
                 RunResult& result, double wall_start, const RunCheckpoint* resume)
    : c_(c),
      solver_(solver),
      observer_(observer),
      mode_(mode),
      result_(result),
      steady_(steady_criterion(c)),
      field_times_(mode == Mode::run ? c.output.field_times : std::vector<double>{}),
      dt_(solver.dt_limits().chosen),
      eps_t_(1e-9 * dt_),
      n_section_(section_samples(c)),
      first_step_(solver.steps()),
      wall_start_(wall_start),
      wall_steps_start_(omp_get_wtime()) {
  outlet_on_ = mode == Mode::run && c.output.outlet_interval > 0.0;
  std::sort(field_times_.begin(), field_times_.end());
  if (resume) {
    wall_before_ = resume->wall_s;
    stepping_before_ = resume->stepping_wall_s;
    steady_.restore(resume->steady);
    window_.assign(resume->average_window.begin(), resume->average_window.end());
    std::istringstream(resume->jitter_state) >> jitter_;
    next_check_ = resume->next_check;
    next_field_ = resume->next_field;
    // The instant after the last sample: a function of the time reached (no state of its own).
    if (outlet_on_)
      next_outlet_ = c.output.outlet_interval *
                     (std::floor(solver.time() / c.output.outlet_interval + 1e-9) + 1.0);
  } else {
    next_check_ = next_interval();
  }
}

double RunLoop::wall_now() const {
  return wall_before_ + omp_get_wtime() - wall_start_;
}
double RunLoop::stepping_now() const {
  return stepping_before_ + omp_get_wtime() - wall_steps_start_;
}

double RunLoop::next_interval() {
  if (mode_ == Mode::warm_start) return c_.time.check_interval;
  return c_.time.check_interval * (0.5 + std::uniform_real_distribution<double>(0.0, 1.0)(jitter_));
}

void RunLoop::sample() {
  ScopedPhase timer(solver_.timers(), Phase::probes);
  last_probes_ =
      solver_.sampler().probe_lines(c_.geometry.length, c_.geometry.half_width, n_section_);
  // A network's other species follow in the same table (split_species): the steady test and
  // the average window then watch every species.
  for (int sp = 1; sp < solver_.species_count(); ++sp) {
    const ProbeTable more =
        solver_.sampler(sp).probe_lines(c_.geometry.length, c_.geometry.half_width, n_section_);
    for (auto [to, from] : {std::pair{&last_probes_.x_mm, &more.x_mm},
                            {&last_probes_.c_y0, &more.c_y0},
                            {&last_probes_.c_yp25, &more.c_yp25},
                            {&last_probes_.c_ym25, &more.c_ym25},
                            {&last_probes_.c_mean, &more.c_mean}})
      to->insert(to->end(), from->begin(), from->end());
  }
  if (mode_ == Mode::run && c_.time.average_window > 0) {
    window_.emplace_back(solver_.time(), last_probes_);
    while (window_.front().first < solver_.time() - c_.time.average_window - eps_t_)
      window_.pop_front();
  }
}

void RunLoop::sample_outlet() {
  ScopedPhase timer(solver_.timers(), Phase::probes);
  const double t = solver_.time(), every = c_.output.outlet_interval;
  // One row per species, in species order (a network's are split at the end of the run,
  // split_outlet): the checkpoint keeps them as one series.
  for (int sp = 0; sp < solver_.species_count(); ++sp) {
    OutletRow row =
        solver_.sampler(sp).outlet_means(c_.geometry.length, c_.geometry.half_width, n_section_);
    row.t = t;
    result_.outlet.push_back(row);
  }
  next_outlet_ = every * (std::floor(t / every + 1e-9) + 1.0);
}

void RunLoop::emit_fields() {
  ScopedPhase timer(solver_.timers(), Phase::output);
  solver_.shed_for_output();
  std::vector<double> pressure_pa;  // freed after the frame: not held between frames
  observer_.on_fields(solver_.frame(pressure_pa));
}

void RunLoop::report_progress(double change) {
  const double t = solver_.time();
  Progress pr;
  pr.t = t;
  pr.t_end = c_.time.t_end;
  pr.step = solver_.steps();
  pr.wall_s = wall_now();
  pr.steps_per_s = (pr.step - first_step_) / std::max(omp_get_wtime() - wall_start_, 1e-9);
  pr.eta_s = (c_.time.t_end - t) / dt_ / std::max(pr.steps_per_s, 1e-9);
  const double t_min = steady_.criterion().t_min;
  if (c_.time.stop_when_steady && t < t_min && t_min < c_.time.t_end)
    pr.eta_steady_s = (t_min - t) / dt_ / std::max(pr.steps_per_s, 1e-9);
  pr.steady_change = change;
  result_.history.push_back({t, stations_from(last_probes_, c_.geometry.length).c_mean, change});
  observer_.on_progress(pr);
}

void RunLoop::checkpoint() {
  ScopedPhase timer(solver_.timers(), Phase::output);
  solver_.shed_for_output();
  RunCheckpoint cp;
  cp.solver = solver_.snapshot();
  cp.steady = steady_.snapshot();
  cp.average_window.assign(window_.begin(), window_.end());
  cp.history = result_.history;
  cp.outlet = result_.outlet;
  std::ostringstream js;
  js << jitter_;
  cp.jitter_state = js.str();
  cp.next_check = next_check_;
  cp.next_field = next_field_;
  cp.wall_s = wall_now();
  cp.stepping_wall_s = stepping_now();
  cp.peak_rss_bytes = std::max(result_.peak_rss_bytes, peak_rss_bytes());
  cp.restarts = result_.restarts;
  cp.warm_started = result_.warm_started;
  cp.warm_start_steady = result_.warm_start_steady;
  cp.warm_start_t = result_.warm_start_t;
  cp.warm_start_steps = result_.warm_start_steps;
  cp.warm_start_wall_s = result_.warm_start_wall_s;
  observer_.on_checkpoint(cp);
}

RunLoop::End RunLoop::run() {
  const bool warm = mode_ == Mode::warm_start;
  const bool stop_when_steady = warm || c_.time.stop_when_steady;
  const long max_steps = warm ? 0 : c_.time.max_steps;
  CheckpointRequest pending = CheckpointRequest::none;
  if (outlet_on_ && result_.outlet.empty()) sample_outlet();  // the start
  while (solver_.time() < c_.time.t_end - eps_t_ &&
         (max_steps == 0 || solver_.steps() < max_steps)) {
    if (!solver_.step(std::min(dt_, c_.time.t_end - solver_.time()))) return End::failed;
    const double t = solver_.time();
    if (outlet_on_ && t >= next_outlet_ - eps_t_) sample_outlet();
    if (t >= next_check_ - eps_t_) {
      next_check_ += next_interval();
      sample();
      const double change = steady_.update(t, last_probes_);
      if (!warm) report_progress(change);
      if (steady_.steady() && stop_when_steady) return End::steady;
    }
    while (next_field_ < field_times_.size() && t >= field_times_[next_field_] - eps_t_) {
      ++next_field_;
      emit_fields();
    }
    if (pending == CheckpointRequest::none) pending = observer_.checkpoint_request(wall_now());
    if (warm) {  // no checkpoints of a warm start: only a stop request is served
      if (pending == CheckpointRequest::write_and_stop) return End::interrupted;
      pending = CheckpointRequest::none;
      continue;
    }
    // Served at a rebuild, where the snapshot is exact (checkpoint.hpp).
    if (pending != CheckpointRequest::none && solver_.just_rebuilt()) {
      checkpoint();
      if (pending == CheckpointRequest::write_and_stop) return End::interrupted;
      pending = CheckpointRequest::none;
    }
  }
  return End::finished;
}

}  // namespace adrsph
