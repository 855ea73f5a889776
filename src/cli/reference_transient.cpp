#include "cli/reference_transient.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>

#include "adrsph/probes.hpp"
#include "adrsph/reference_network_transient.hpp"
#include "adrsph/reference_transient.hpp"
#include "cli/commands.hpp"

namespace adrsph::cli {
namespace {

namespace fs = std::filesystem;
namespace ref = adrsph::reference;

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file.string() + ": cannot read");
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

void print_summary(const ref::TransientSolution& s, const ref::Problem& p) {
  const ref::TransientReport& r = s.report;
  std::printf("transient reference %dx%d  D=%g k=%g Pe=%g  %s\n", s.final.grid.nx, s.final.grid.ny,
              p.D, p.k, p.peclet(), r.solver.c_str());
  std::printf("  dt = %.4g s, %ld steps to t = %.4g s, %s; %.2f sweeps per step (max %d)%s\n", r.dt,
              r.steps, s.t_reached, r.started_at_rest ? "BDF2 from rest" : "implicit-Euler start",
              static_cast<double>(r.corrections) / static_cast<double>(std::max(1L, r.steps)),
              r.max_step_corrections, r.converged ? "" : "  (NOT CONVERGED)");
  std::printf("  assembly %.2f s, factorisation %.2f s, steps %.2f s\n", r.assembly_seconds,
              r.factor_seconds, r.step_seconds);
  const auto peak =
      std::max_element(s.outlet.begin(), s.outlet.end(),
                       [](const OutletRow& a, const OutletRow& b) { return a.c_flow < b.c_flow; });
  std::printf("  outlet: %zu samples, C_flow peak %.6g at t = %.4g s, last %.3g\n", s.outlet.size(),
              peak->c_flow, peak->t, s.outlet.back().c_flow);
  const ref::TransientBalance& b = s.balance;
  std::printf(
      "  balance (amount / flow rate, mol/m^3 s): in %.6g, out %.6g, reacted %.6g, held %.6g "
      "-> %.6g\n",
      b.inflow, b.outflow, b.reacted, b.held_initial, b.held_final);
}

void print_network_summary(const ref::NetworkTransientSolution& s, const Case& c) {
  const ref::TransientReport& r = s.report;
  std::printf("transient network reference %dx%d, %d species  %s\n", s.final.grid.nx,
              s.final.grid.ny, c.species_count(), r.solver.c_str());
  std::printf(
      "  dt = %.4g s, %ld steps to t = %.4g s, %s; %.2f iterations per step (max "
      "%d)%s\n",
      r.dt, r.steps, s.t_reached, r.started_at_rest ? "BDF2 from rest" : "implicit-Euler start",
      static_cast<double>(r.corrections) / static_cast<double>(std::max(1L, r.steps)),
      r.max_step_corrections, r.converged ? "" : "  (NOT CONVERGED)");
  std::printf("  assembly %.2f s, factorisation %.2f s, steps %.2f s\n", r.assembly_seconds,
              r.factor_seconds, r.step_seconds);
  std::printf("  %-8s %10s %10s %12s %12s %12s %10s\n", "species", "peak", "at t [s]", "in", "out",
              "reacted", "held");
  for (int k = 0; k < c.species_count(); ++k) {
    const auto& rows = s.outlet[static_cast<std::size_t>(k)];
    const auto peak = std::max_element(
        rows.begin(), rows.end(),
        [](const OutletRow& a, const OutletRow& b) { return a.c_flow < b.c_flow; });
    const ref::TransientBalance& b = s.balance[static_cast<std::size_t>(k)];
    std::printf("  %-8s %10.6g %10.4g %12.6g %12.6g %12.6g %10.3g\n", c.species_at(k).name.c_str(),
                peak->c_flow, peak->t, b.inflow, b.outflow, b.reacted, b.held_final);
  }
  std::printf("  (amounts / flow rate, mol/m^3 s; reacted = net consumption)\n");
}

// DIR/case.toml: the case file as given (its --set values are in run.json).
void copy_case(const fs::path& from, const fs::path& dir) {
  const std::string text = read_text(from);
  std::ofstream case_copy(dir / "case.toml", std::ios::binary | std::ios::trunc);
  case_copy << text;
  case_copy.close();
  if (!case_copy) throw std::runtime_error((dir / "case.toml").string() + ": write failed");
}

// A line on stderr at every tenth of t_end: runs on fine grids take minutes.
std::function<void(double)> progress_reporter(double t_end) {
  const auto start = std::chrono::steady_clock::now();
  auto next_report = std::make_shared<double>(0.1 * t_end);
  return [=](double t) {
    if (t < *next_report - 1e-12) return;
    *next_report += 0.1 * t_end;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "  t = %.4g / %.4g s, %.0f s\n", t, t_end, elapsed);
  };
}

// Builds the case's problem, solves it with the request's grid, step and solver, and times
// the solve. Returns kExitOk, or the exit code of the failure it reported: bad input (a case
// or an option the solver does not take), or a failed solve.
template <class Problem, class Solution, class Make, class Solve>
int solve_request(const TransientRequest& q, const Case& c, Make make, Solve solve, Problem& p,
                  Solution& s, double& wall) {
  try {
    p = make(c);
  } catch (const std::invalid_argument& e) {
    std::cerr << "adrsph reference: " << q.case_file.string() << ": " << e.what() << "\n";
    return kExitBadInput;
  }
  ref::TransientOptions opt;
  opt.solver = q.solver;
  opt.limiter = q.limiter;
  opt.dt = q.dt > 0.0 ? q.dt : ref::default_transient_dt(c);
  opt.on_sample = progress_reporter(c.time.t_end);
  const auto start = std::chrono::steady_clock::now();
  try {
    s = solve(p, q.nx, q.ny, opt);
  } catch (const std::invalid_argument& e) {
    std::cerr << "adrsph reference: " << q.case_file.string() << ": " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "adrsph reference: " << e.what() << "\n";
    return kExitRunFailed;
  }
  wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return kExitOk;
}

// The network of a case with several [[species]] (reference_network_transient.hpp): every
// species' outlet series under the name an SPH run gives it.
int run_network_transient_reference(const TransientRequest& q, const Case& c) {
  ref::NetworkTransientProblem p;
  ref::NetworkTransientSolution s;
  double wall = 0.0;
  if (const int rc = solve_request(q, c, ref::network_transient_problem_from_case,
                                   ref::solve_network_transient, p, s, wall);
      rc != kExitOk)
    return rc;
  print_network_summary(s, c);
  std::string names;
  try {
    fs::create_directories(q.out_dir);
    for (int k = 0; k < c.species_count(); ++k) {
      // The first species keeps a one-species run's file name; another gets _<name>.
      const std::string file =
          k == 0 ? std::string("outlet.csv") : "outlet_" + c.species_at(k).name + ".csv";
      write_outlet_csv(q.out_dir / file, s.outlet[static_cast<std::size_t>(k)]);
      names += file + ",";
    }
    copy_case(q.case_file, q.out_dir);
    ref::write_network_transient_run_json(q.out_dir / "run.json", c, q.overrides, s, wall);
  } catch (const std::exception& e) {
    std::cerr << "adrsph reference: " << e.what() << "\n";
    return kExitIoError;
  }
  std::printf(
      "  wall %.1f s; wrote %s/{%scase.toml,run.json} (adrsph rtd --species and "
      "adrsph compare read it)\n",
      wall, q.out_dir.string().c_str(), names.c_str());
  return s.report.converged ? kExitOk : kExitRunFailed;
}

}  // namespace

int run_transient_reference(const TransientRequest& q, const Case& c) {
  if (!(c.output.outlet_interval > 0.0)) {
    std::cerr << "adrsph reference: " << q.case_file.string()
              << ": output.outlet_interval is 0, and --transient writes the outlet series "
                 "(outlet.csv) at that interval; set it, e.g. --set "
                 "output.outlet_interval=0.01\n";
    return kExitBadInput;
  }
  if (c.species_count() > 1) return run_network_transient_reference(q, c);
  // A case the reference cannot solve (problem_from_case throws std::invalid_argument) is
  // bad input, like a bad grid or step.
  ref::TransientProblem p;
  ref::TransientSolution s;
  double wall = 0.0;
  if (const int rc =
          solve_request(q, c, ref::transient_problem_from_case, ref::solve_transient, p, s, wall);
      rc != kExitOk)
    return rc;
  print_summary(s, p.space);
  try {
    fs::create_directories(q.out_dir);
    write_outlet_csv(q.out_dir / "outlet.csv", s.outlet);
    copy_case(q.case_file, q.out_dir);
    ref::write_transient_run_json(q.out_dir / "run.json", c, q.overrides, s, wall);
  } catch (const std::exception& e) {
    std::cerr << "adrsph reference: " << e.what() << "\n";
    return kExitIoError;
  }
  std::printf("  wall %.1f s; wrote %s/{outlet.csv,case.toml,run.json} (adrsph rtd reads it)\n",
              wall, q.out_dir.string().c_str());
  return s.report.converged ? kExitOk : kExitRunFailed;
}

}  // namespace adrsph::cli
