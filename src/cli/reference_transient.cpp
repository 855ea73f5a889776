#include "cli/reference_transient.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include "adrsph/probes.hpp"
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

}  // namespace

int run_transient_reference(const TransientRequest& q, const Case& c) {
  if (!(c.output.outlet_interval > 0.0)) {
    std::cerr << "adrsph reference: " << q.case_file.string()
              << ": output.outlet_interval is 0, and --transient writes the outlet series "
                 "(outlet.csv) at that interval; set it, e.g. --set "
                 "output.outlet_interval=0.01\n";
    return kExitBadInput;
  }
  // A case the reference cannot solve (problem_from_case throws std::invalid_argument) is
  // bad input, like a bad grid or step.
  ref::TransientProblem p;
  try {
    p = ref::transient_problem_from_case(c);
  } catch (const std::invalid_argument& e) {
    std::cerr << "adrsph reference: " << q.case_file.string() << ": " << e.what() << "\n";
    return kExitBadInput;
  }
  ref::TransientOptions opt;
  opt.solver = q.solver;
  opt.limiter = q.limiter;
  opt.dt = q.dt > 0.0 ? q.dt : ref::default_transient_dt(c);
  // A line on stderr at every tenth of t_end: runs on fine grids take minutes.
  const auto start = std::chrono::steady_clock::now();
  double next_report = 0.1 * c.time.t_end;
  opt.on_sample = [&](double t) {
    if (t < next_report - 1e-12) return;
    next_report += 0.1 * c.time.t_end;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "  t = %.4g / %.4g s, %.0f s\n", t, c.time.t_end, elapsed);
  };

  ref::TransientSolution s;
  try {
    s = ref::solve_transient(p, q.nx, q.ny, opt);
  } catch (const std::invalid_argument& e) {
    std::cerr << "adrsph reference: " << q.case_file.string() << ": " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "adrsph reference: " << e.what() << "\n";
    return kExitRunFailed;
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  print_summary(s, p.space);
  try {
    fs::create_directories(q.out_dir);
    write_outlet_csv(q.out_dir / "outlet.csv", s.outlet);
    const std::string text = read_text(q.case_file);
    std::ofstream case_copy(q.out_dir / "case.toml", std::ios::binary | std::ios::trunc);
    case_copy << text;
    case_copy.close();
    if (!case_copy) throw std::runtime_error((q.out_dir / "case.toml").string() + ": write failed");
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
