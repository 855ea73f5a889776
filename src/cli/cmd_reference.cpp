// `adrsph reference`: the steady finite-volume reference of a case (docs/benchmark.md, section 5,
// issue 4). Writes DIR/probes.csv, DIR/stations.csv, DIR/reference.h5, DIR/reference.json;
// with --convergence also solves on nx/4, nx/2, nx, 2nx and prints the convergence table;
// with --transient solves in time instead (cli/reference_transient.cpp).
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "adrsph/case.hpp"
#include "adrsph/probes.hpp"
#include "adrsph/reference.hpp"
#include "cli/commands.hpp"
#include "cli/reference_network.hpp"
#include "cli/reference_transient.hpp"

namespace adrsph::cli {
namespace {

namespace ref = adrsph::reference;

struct ReferenceOptions {
  std::string case_file;
  std::vector<std::string> overrides;
  int nx = 1600, ny = 160;
  std::string out_dir;
  bool convergence = false;
  bool transient = false;
  double dt = 0.0;                          // --dt [s], transient only; 0: the default
  bool nx_given = false, ny_given = false;  // on the command line (--transient has its own)
  ref::LinearSolver solver = ref::LinearSolver::sparse_lu;
  ref::Limiter limiter = ref::Limiter::van_leer;
};

void write_outputs(const std::filesystem::path& dir, const std::string& name,
                   const ref::Solution& s, const ref::Problem& p) {
  std::filesystem::create_directories(dir);
  write_probes_csv(dir / "probes.csv", ref::probe_table(s, p));
  write_stations_csv(dir / "stations.csv", ref::station_table(s, p));
  ref::write_reference_h5(dir / "reference.h5", s, p);
  ref::write_reference_json(dir / "reference.json", name, s, p);
}

void print_solve(const ref::Solution& s, const ref::Problem& p) {
  const ref::SolveReport& r = s.report;
  std::printf("reference %dx%d  D=%g k=%g Pe=%g  %s\n", s.grid.nx, s.grid.ny, p.D, p.k, p.peclet(),
              r.solver.c_str());
  std::printf(
      "  assembly %.2f s, solve %.2f s, %d corrections, last change %.1e, residual %.1e%s\n",
      r.assembly_seconds, r.solve_seconds, r.corrections, r.last_change, r.residual,
      r.converged ? "" : "  (NOT CONVERGED)");
  const StationTable st = ref::station_table(s, p);
  for (std::size_t m = 0; m < st.x_mm.size(); ++m)
    std::printf("  section average at x = %g mm: %.8f\n", st.x_mm[m], st.c_mean[m]);
}

int run_convergence(const ReferenceOptions& o, const ref::Problem& p, const ref::SolverOptions& so,
                    const std::filesystem::path& dir, const std::string& name) {
  const int factors[][2] = {{1, 4}, {1, 2}, {1, 1}, {2, 1}};  // nx * a / b
  std::vector<ref::ConvergenceLevel> levels;
  for (const auto& f : factors) {
    const int nx = o.nx * f[0] / f[1], ny = o.ny * f[0] / f[1];
    if (nx < 2 || ny < 1) continue;
    std::printf("solving %dx%d ...\n", nx, ny);
    std::fflush(stdout);
    const ref::Solution s = ref::solve_steady(p, nx, ny, so);
    std::printf("  %.2f s (%d corrections, residual %.1e%s)\n",
                s.report.assembly_seconds + s.report.solve_seconds, s.report.corrections,
                s.report.residual, s.report.converged ? "" : ", NOT CONVERGED");
    levels.push_back({nx, ny, ref::station_table(s, p), s.report});
    if (nx == o.nx) write_outputs(dir, name, s, p);
  }
  const std::string table = ref::convergence_table(levels);
  std::printf("\nGrid convergence, D=%g k=%g Pe=%g (%s limiter):\n\n%s\n", p.D, p.k, p.peclet(),
              ref::to_string(o.limiter), table.c_str());
  const ref::ConvergenceVerdict v = ref::convergence_verdict(levels, o.nx);
  const char* verdict = !v.checked ? "NOT CHECKED" : v.pass ? "PASS" : "FAIL";
  std::printf(
      "%s: largest relative change of a station average from %dx%d to %dx%d: %.2e "
      "(must be < 1e-4, docs/benchmark.md, section 5)\n",
      verdict, o.nx, o.ny, 2 * o.nx, 2 * o.ny, v.max_change);
  std::FILE* f = std::fopen((dir / "convergence.md").c_str(), "w");
  if (f) {
    std::fprintf(f, "# Grid convergence, D=%g k=%g Pe=%g\n\n%s\n%s: max relative change %.2e\n",
                 p.D, p.k, p.peclet(), table.c_str(), verdict, v.max_change);
    std::fclose(f);
  }
  return kExitOk;
}

// The transient mode's default grid (docs/reference.md, "Transient mode": its convergence).
constexpr int kTransientNx = 400, kTransientNy = 40;

int run_reference(const ReferenceOptions& o) {
  if (o.transient && o.convergence) {
    std::cerr << "adrsph reference: --transient and --convergence exclude each other: "
                 "--convergence studies the steady solution; the transient solution's "
                 "convergence is measured by running --transient at two --nx/--ny and --dt "
                 "(docs/reference.md, \"Transient mode\")\n";
    return kExitBadInput;
  }
  if (o.dt > 0.0 && !o.transient) {
    std::cerr << "adrsph reference: --dt needs --transient (the steady solve has no time step)\n";
    return kExitBadInput;
  }
  Case c;
  try {
    c = load_case(o.case_file, o.overrides);
  } catch (const CaseError& e) {
    std::cerr << "adrsph reference: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "adrsph reference: " << o.case_file << ": " << e.what() << "\n";
    return kExitBadInput;
  }
  if (o.transient) {
    TransientRequest q;
    q.case_file = o.case_file;
    q.overrides = o.overrides;
    q.nx = o.nx_given ? o.nx : kTransientNx;
    q.ny = o.ny_given ? o.ny : kTransientNy;
    q.dt = o.dt;
    q.out_dir = o.out_dir.empty()
                    ? std::filesystem::path("runs") / ("reference_transient_" + c.name)
                    : std::filesystem::path(o.out_dir);
    q.solver = o.solver;
    q.limiter = o.limiter;
    return run_transient_reference(q, c);
  }
  const std::filesystem::path dir = o.out_dir.empty()
                                        ? std::filesystem::path("runs") / ("reference_" + c.name)
                                        : std::filesystem::path(o.out_dir);
  if (c.species_count() > 1) {
    NetworkRequest q;
    q.nx = o.nx_given ? o.nx : kNetworkNx;
    q.ny = o.ny_given ? o.ny : kNetworkNy;
    q.convergence = o.convergence;
    q.out_dir = dir;
    q.solver.solver = o.solver;
    q.solver.limiter = o.limiter;
    return run_network_reference(q, c);
  }
  ref::Problem p;
  try {
    p = ref::problem_from_case(c);
  } catch (const std::invalid_argument& e) {
    std::cerr << "adrsph reference: " << o.case_file << ": " << e.what() << "\n";
    return kExitBadInput;
  }
  ref::SolverOptions so;
  so.solver = o.solver;
  so.limiter = o.limiter;
  if (o.convergence) {
    try {
      return run_convergence(o, p, so, dir, c.name);
    } catch (const std::exception& e) {
      std::cerr << "adrsph reference: " << e.what() << "\n";
      return kExitRunFailed;
    }
  }
  std::unique_ptr<ref::Solution> s;
  try {
    s = std::make_unique<ref::Solution>(ref::solve_steady(p, o.nx, o.ny, so));
  } catch (const std::invalid_argument& e) {
    std::cerr << "adrsph reference: " << o.case_file << ": " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "adrsph reference: " << e.what() << "\n";
    return kExitRunFailed;
  }
  print_solve(*s, p);
  try {
    write_outputs(dir, c.name, *s, p);
  } catch (const std::exception& e) {
    std::cerr << "adrsph reference: " << e.what() << "\n";
    return kExitIoError;
  }
  std::printf("  wrote %s/{probes.csv,stations.csv,reference.h5,reference.json}\n",
              dir.string().c_str());
  return s->report.converged ? kExitOk : kExitRunFailed;
}

}  // namespace

Command register_reference(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "reference",
      "Steady finite-volume reference solution of a case (docs/benchmark.md, section 5): "
      "u(y) dC/dx = "
      "D lap C - R(C) on a structured grid (R: species.k and the [[reaction]] tables), van "
      "Leer TVD advection, Eigen SparseLU. Writes DIR/probes.csv, stations.csv, reference.h5, "
      "reference.json. DIR defaults to runs/reference_<case name>.\n"
      "A case of several [[species]] is solved as a network (Newton on the coupled species, "
      "default grid 800x80) and writes probes_<name>.csv and stations_<name>.csv for every "
      "species after the first; --convergence then also solves nx/2 x ny/2 and prints the "
      "change of each station.\n"
      "With --transient: dC/dt + u dC/dx = D lap C - R(C) from species.c_init "
      "with the inlet "
      "[species.feed] to time.t_end (BDF2), writing the outlet series DIR/outlet.csv every "
      "output.outlet_interval (which must be > 0), DIR/case.toml and DIR/run.json, which "
      "`adrsph rtd DIR` reads like a run; DIR defaults to runs/reference_transient_<case "
      "name>. A network is solved in time the same way (Newton on the coupled species in "
      "each step), every species after the first writing DIR/outlet_<name>.csv.\n"
      "Exit codes: 0 ok, 1 I/O error, 2 bad input (case file, key, value, option), 3 the "
      "solve failed or did not converge.");
  auto o = std::make_shared<ReferenceOptions>();
  sub->add_option("case", o->case_file, "Case file (TOML)")->required();
  sub->add_option("--set", o->overrides,
                  "Override a case key, e.g. --set species.D=0.1 (dotted key, TOML value). "
                  "Repeatable")
      ->allow_extra_args(false);
  auto* nx = sub->add_option("--nx", o->nx,
                             "Cells along x (default 1600, the paper's mesh; 400 with --transient)")
                 ->check(CLI::Range(2, 1 << 20));
  auto* ny = sub->add_option("--ny", o->ny, "Cells across y (default 160; 40 with --transient)")
                 ->check(CLI::Range(1, 1 << 20));
  sub->add_option("--out", o->out_dir,
                  "Output directory (default runs/reference_<case name>, with --transient "
                  "runs/reference_transient_<case name>)")
      ->check(kNonEmptyPath);
  sub->add_flag("--convergence", o->convergence,
                "Solve on nx/4, nx/2, nx and 2nx (x ny likewise; 3200x320 takes ~40 s and "
                "2.3 GB), print station averages, relative changes, observed orders and "
                "PASS/FAIL of the 1e-4 criterion; writes DIR/convergence.md");
  sub->add_flag("--transient", o->transient,
                "Solve in time from species.c_init with the inlet [species.feed] to time.t_end "
                "(BDF2) and write the outlet series outlet.csv (outlet_<name>.csv for a "
                "network's other species) every output.outlet_interval, "
                "case.toml and run.json: a directory `adrsph rtd` reads. Not with "
                "--convergence");
  sub->add_option("--dt", o->dt,
                  "Time step of --transient [s] (default: from the feeds' shortest feature and "
                  "output.outlet_interval, docs/reference.md); rounded down to divide "
                  "output.outlet_interval")
      ->check(CLI::PositiveNumber);
  const std::map<std::string, ref::LinearSolver> solvers{
      {"lu", ref::LinearSolver::sparse_lu}, {"bicgstab", ref::LinearSolver::bicgstab_ilut}};
  sub->add_option("--solver", o->solver, "Linear solver: lu (SparseLU, default) or bicgstab")
      ->transform(CLI::CheckedTransformer(solvers, CLI::ignore_case));
  const std::map<std::string, ref::Limiter> limiters{{"van_leer", ref::Limiter::van_leer},
                                                     {"minmod", ref::Limiter::minmod},
                                                     {"upwind", ref::Limiter::upwind}};
  sub->add_option("--limiter", o->limiter, "Advection: van_leer (default), minmod, upwind")
      ->transform(CLI::CheckedTransformer(limiters, CLI::ignore_case));
  return {sub, [o, nx, ny] {
            o->nx_given = nx->count() > 0;
            o->ny_given = ny->count() > 0;
            return run_reference(*o);
          }};
}

}  // namespace adrsph::cli
