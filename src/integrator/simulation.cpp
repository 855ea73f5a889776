// A run: its solver (new, warm-started or continued from a checkpoint), its stepping loop
// (run_loop.hpp) and the result it reports.
#include <omp.h>

#include <algorithm>
#include <deque>

#include "adrsph/simulation.hpp"
#include "analysis/steady_state.hpp"
#include "boundaries/channel_scene.hpp"
#include "case/failure_advice.hpp"
#include "integrator/run_loop.hpp"
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
  RunResult own;  // the loop's history and checkpoint fields: none kept for a warm start
  RunLoop loop(pre, solver, observer, RunLoop::Mode::warm_start, own, wall0);
  switch (loop.run()) {
    case RunLoop::End::failed:
      throw WarmStartFailed(
          "the warm start (species in the prescribed flow) failed: " + solver.failure() + " " +
          failure_advice(solver.failure_kind(), pre, 0.0) + " Or set time.warm_start = false.");
    case RunLoop::End::interrupted:
      throw RunInterrupted("interrupted during the warm start (no checkpoint yet)");
    case RunLoop::End::steady:
    case RunLoop::End::finished:
      break;
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
  result.warm_start_steady = loop.steady().steady();
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
  if (resume) {
    result.restarts = resume->restarts + 1;
    result.peak_rss_bytes = resume->peak_rss_bytes;
    result.warm_started = resume->warm_started;
    result.warm_start_steady = resume->warm_start_steady;
    result.warm_start_t = resume->warm_start_t;
    result.warm_start_steps = resume->warm_start_steps;
    result.warm_start_wall_s = resume->warm_start_wall_s;
    result.history = resume->history;
    result.outlet = resume->outlet;
  }
  SphSolver solver = make_solver(c, observer, result, resume);
  result.dt = solver.dt_limits();
  result.probe_interpolation = probe_interpolation_text(section_samples(c));
  RunLoop loop(c, solver, observer, RunLoop::Mode::run, result, wall_start, resume);
  result.steady_criterion = {loop.steady().criterion().tol, loop.steady().criterion().window,
                             loop.steady().criterion().t_min};
  const RunLoop::End end = loop.run();

  result.t_reached = solver.time();
  result.steps = solver.steps();
  result.n_particles = solver.particles().size();
  result.n_fluid = solver.fluid_count();
  result.peak_rss_bytes = std::max(result.peak_rss_bytes, peak_rss_bytes());
  result.engine_bytes = {solver.particle_bytes(), solver.list_bytes(),
                         solver.diffusion_weight_bytes(), solver.pair_record_bytes()};
  result.balance_flow_rate = 2.0 * c.geometry.half_width * (2.0 / 3.0) * c.u_max();
  result.species_balance.clear();
  for (int e = 0; e < c.species_count(); ++e) {
    const SpeciesLedger& l = solver.species_ledger(e);
    const double q = result.balance_flow_rate;
    result.species_balance.push_back({c.species_at(e).name, l.inflow / q, l.outflow / q,
                                      l.reaction / q, solver.species_inventory(e) / q});
  }
  if (end == RunLoop::End::interrupted) {
    result.status = "interrupted";
    result.message =
        "stopped on request after a checkpoint at t = " + std::to_string(solver.time()) +
        " s; continue with adrsph run --restart";
    result.wall_s = loop.wall_now();
    return result;
  }
  const bool ok = end != RunLoop::End::failed;
  if (!ok) {
    result.status = "failed";
    const SphSolver::FailureSite& f = solver.failure_site();
    result.message = solver.failure() + " " +
                     failure_advice(f.kind, c, solver.dt_limits().acoustic, f.step == 1);
    result.failure = {failure_name(f.kind), f.t, f.step, f.x, f.y, f.value};
  }
  // Final probes: instantaneous, or the mean over the final window.
  if (c.time.average_window > 0 && !loop.window().empty() && ok) {
    result.probes = average(loop.window());
    result.average_window = loop.window().back().first - loop.window().front().first;
  } else {
    loop.sample();
    result.probes = loop.last_probes();
  }
  if (c.species_count() > 1) {
    std::vector<std::vector<OutletRow>> outlets = split_outlet(result.outlet, c.species_count());
    result.outlet = outlets[0];
    result.more_outlet.assign(outlets.begin() + 1, outlets.end());
    const std::vector<ProbeTable> parts = split_species(result.probes, c.species_count());
    result.probes = parts[0];
    for (int sp = 1; sp < c.species_count(); ++sp)
      result.more_species.push_back(
          {c.species_at(sp).name, parts[static_cast<std::size_t>(sp)],
           stations_from(parts[static_cast<std::size_t>(sp)], c.geometry.length)});
  }
  result.stations = stations_from(result.probes, c.geometry.length);
  solver.release_stepping_memory();
  loop.emit_fields();
  // After the final frame: HDF5's code and buffers count in the run's peak.
  result.peak_rss_bytes = std::max(result.peak_rss_bytes, peak_rss_bytes());

  result.wall_s = loop.wall_now();
  // Throughput of the stepping alone (set-up and warm start excluded).
  result.particle_steps_per_s = solver.particle_steps() / std::max(loop.stepping_now(), 1e-9);
  result.list_rebuilds = solver.list_rebuilds();
  result.list_two_pass_builds = solver.list_two_pass_builds();
  result.mean_neighbours = solver.mean_neighbours();
  result.steady = loop.steady().steady();
  result.t_steady = loop.steady().t_steady();
  result.lost_particles = solver.lost_particles();
  result.phase_seconds = solver.timers().table();
  return result;
}

}  // namespace adrsph
