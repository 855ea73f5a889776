// End-of-run summary: case, numbers, phase timers, station averages, where the files are.
#include "cli/run_summary.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

namespace adrsph::cli {
namespace {

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

void print_phases(std::ostream& os, const RunResult& r) {
  if (r.phase_seconds.empty()) return;
  double total = 0.0;
  for (const auto& [name, s] : r.phase_seconds) total += s;
  char buf[128];
  std::snprintf(buf, sizeof buf, "  %-24s %10s %7s\n", "phase", "seconds", "%");
  os << buf;
  for (const auto& [name, s] : r.phase_seconds) {
    std::snprintf(buf, sizeof buf, "  %-24s %10.3f %6.1f%%\n", name.c_str(), s,
                  total > 0 ? 100.0 * s / total : 0.0);
    os << buf;
  }
}

// "A (D = 10), B (D = 10), ...": the species of a network.
std::string species_list(const Case& c) {
  std::string out;
  for (int s = 0; s < c.species_count(); ++s)
    out += (s ? ", " : "") + c.species_at(s).name + " (D = " + fmt("%g", c.species_at(s).D) + ")";
  return out;
}

}  // namespace

void print_summary(std::ostream& os, const Case& c, const RunResult& r, const SummaryInfo& s) {
  const double wall = r.wall_s > 0 ? r.wall_s : s.wall_s;
  os << "\nadrsph run: " << c.name << "  (" << c.source.string() << ")\n"
     << "  scheme " << to_string(c.scheme) << ", flow " << to_string(c.flow) << ", Pe "
     << fmt("%g", c.peclet()) << " (D = " << fmt("%g", c.species.D)
     << " mm^2/s, k = " << fmt("%g", c.species.k) << " 1/s), dx " << fmt("%g", c.particles.dx)
     << " mm\n"
     << (c.more_species.empty()
             ? std::string()
             : "  species: " + species_list(c) + " (D, k above: " + c.species.name + ")\n")
     << (c.reactions.empty() ? std::string()
                             : "  reactions: " + std::to_string(c.reactions.size()) +
                                   " [[reaction]] table(s) besides species.k\n")
     << "  particles " << r.n_particles << " (fluid " << r.n_fluid << "), threads " << s.threads
     << "\n"
     << "  steps " << r.steps << ", simulated " << fmt("%.4g", r.t_reached) << " s of "
     << fmt("%g", c.time.t_end) << " s, wall " << fmt("%.2f", wall) << " s, "
     << fmt("%.3g", r.particle_steps_per_s) << " particle-steps/s\n";
  if (r.dt.chosen > 0)
    os << "  dt " << fmt("%.3g", r.dt.chosen) << " s ("
       << (r.dt.binding.empty() ? "?" : r.dt.binding) << " limit)\n";
  os << "  steady state: "
     << (r.steady ? "yes, at t = " + fmt("%.4g", r.t_steady) + " s" : std::string("no")) << "\n";
  if (r.steps > 0)
    os << "  neighbour lists: " << r.list_rebuilds << " builds (one per "
       << fmt("%.3g", static_cast<double>(r.steps) / std::max(1L, r.list_rebuilds)) << " steps, "
       << r.list_two_pass_builds << " in two passes), " << fmt("%.1f", r.mean_neighbours)
       << " entries per particle\n";
  if (r.lost_particles > 0) os << "  lost particles: " << r.lost_particles << "\n";
  print_phases(os, r);
  auto stations = [&](const std::string& label, const StationTable& st) {
    if (st.x_mm.empty()) return;
    os << "  section average " << label << ":";
    for (std::size_t i = 0; i < st.x_mm.size() && i < st.c_mean.size(); ++i)
      os << "  x = " << fmt("%g", st.x_mm[i]) << ": " << fmt("%.5f", st.c_mean[i]);
    os << " mol/m^3";
    if (r.average_window > 0)
      os << " (averaged over the last " << fmt("%g", r.average_window) << " s)";
    os << "\n";
  };
  stations(c.more_species.empty() ? std::string("C") : c.species.name, r.stations);
  for (const RunResult::SpeciesProbes& sp : r.more_species) stations(sp.name, sp.stations);
  os << "  status: " << r.status;
  if (!r.message.empty()) os << " (" << r.message << ")";
  os << "\n  files in " << s.out_dir.string() << "/:";
  for (std::size_t i = 0; i < s.files.size(); ++i) os << (i ? ", " : " ") << s.files[i];
  os << "\n";
}

}  // namespace adrsph::cli
