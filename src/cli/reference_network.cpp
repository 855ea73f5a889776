#include "cli/reference_network.hpp"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "adrsph/probes.hpp"
#include "adrsph/reference_network.hpp"
#include "cli/commands.hpp"

namespace adrsph::cli {
namespace {

namespace ref = adrsph::reference;

// The first species writes the files of a one-species reference, the others their own.
std::string suffix(const ref::NetworkProblem& p, int s) {
  return s == 0 ? std::string() : "_" + p.species[static_cast<std::size_t>(s)].name;
}

void write_network(const std::filesystem::path& dir, const std::string& name,
                   const ref::NetworkSolution& sol, const ref::NetworkProblem& p) {
  std::filesystem::create_directories(dir);
  for (int s = 0; s < static_cast<int>(p.species.size()); ++s) {
    const ref::Problem one = p.species_problem(s);
    const ref::Solution field = sol.species_solution(s);
    write_probes_csv(dir / ("probes" + suffix(p, s) + ".csv"), ref::probe_table(field, one));
    write_stations_csv(dir / ("stations" + suffix(p, s) + ".csv"), ref::station_table(field, one));
    if (s == 0) {
      ref::write_reference_h5(dir / "reference.h5", field, one);
      ref::write_reference_json(dir / "reference.json", name, field, one);
    }
  }
}

ref::NetworkSolution solve(const ref::NetworkProblem& p, int nx, int ny,
                           const ref::SolverOptions& so) {
  std::printf("solving the network of %zu species on %dx%d ...\n", p.species.size(), nx, ny);
  std::fflush(stdout);
  ref::NetworkSolution s = ref::solve_network_steady(p, nx, ny, so);
  const ref::SolveReport& r = s.report;
  std::printf(
      "  %s\n  assembly %.2f s, solve %.2f s, %d iterations, last change %.1e, "
      "residual %.1e%s\n",
      r.solver.c_str(), r.assembly_seconds, r.solve_seconds, r.corrections, r.last_change,
      r.residual, r.converged ? "" : "  (NOT CONVERGED)");
  return s;
}

std::vector<StationTable> stations_of(const ref::NetworkSolution& s, const ref::NetworkProblem& p) {
  std::vector<StationTable> out;
  for (int k = 0; k < static_cast<int>(p.species.size()); ++k)
    out.push_back(ref::station_table(s.species_solution(k), p.species_problem(k)));
  return out;
}

}  // namespace

int run_network_reference(const NetworkRequest& q, const Case& c) {
  ref::NetworkProblem p;
  try {
    p = ref::network_problem_from_case(c);
  } catch (const std::invalid_argument& e) {
    std::cerr << "adrsph reference: " << c.source.string() << ": " << e.what() << "\n";
    return kExitBadInput;
  }
  ref::NetworkSolution s, coarse;
  try {
    s = solve(p, q.nx, q.ny, q.solver);
    if (q.convergence) coarse = solve(p, q.nx / 2, std::max(1, q.ny / 2), q.solver);
  } catch (const std::invalid_argument& e) {
    std::cerr << "adrsph reference: " << c.source.string() << ": " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "adrsph reference: " << e.what() << "\n";
    return kExitRunFailed;
  }
  const std::vector<StationTable> st = stations_of(s, p);
  const std::vector<StationTable> st_coarse =
      q.convergence ? stations_of(coarse, p) : std::vector<StationTable>{};
  for (std::size_t k = 0; k < st.size(); ++k) {
    std::printf("  %s (D = %g, c_in = %g):", p.species[k].name.c_str(), p.species[k].D,
                p.species[k].c_in);
    for (std::size_t m = 0; m < st[k].x_mm.size(); ++m) {
      std::printf("  x = %g: %.8f", st[k].x_mm[m], st[k].c_mean[m]);
      if (q.convergence)
        std::printf(" (%dx%d: %+.1e)", q.nx / 2, std::max(1, q.ny / 2),
                    (st_coarse[k].c_mean[m] - st[k].c_mean[m]) /
                        std::max(std::fabs(st[k].c_mean[m]), 1e-300));
    }
    std::printf("\n");
  }
  try {
    write_network(q.out_dir, c.name, s, p);
  } catch (const std::exception& e) {
    std::cerr << "adrsph reference: " << e.what() << "\n";
    return kExitIoError;
  }
  std::printf("  wrote %s/{probes,stations}[_<species>].csv, reference.h5, reference.json\n",
              q.out_dir.string().c_str());
  return s.report.converged ? kExitOk : kExitRunFailed;
}

}  // namespace adrsph::cli
