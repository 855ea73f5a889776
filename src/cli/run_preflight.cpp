#include "cli/run_preflight.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <utility>

#include "boundaries/channel_scene.hpp"
#include "integrator/time_step.hpp"

namespace adrsph::cli {
namespace {

std::string num(double v, int digits = 3) {
  std::ostringstream os;
  os.precision(digits);
  os << v;
  return os.str();
}

std::string bytes_text(double b) {
  const char* units[] = {"B", "kB", "MB", "GB", "TB", "PB", "EB"};
  int u = 0;
  while (b >= 1000.0 && u < 6) {
    b /= 1000.0;
    ++u;
  }
  return num(b) + " " + units[u];
}

// The particle count: memory and the 32-bit particle indices of the neighbour lists.
std::optional<PreflightProblem> check_memory(const Case& c, double available) {
  const double n = channel_particle_estimate(c);
  const double need = kFixedBytes + kBytesPerParticle * n;
  // The spacing at which the same case would fit (n grows as 1/dx^2).
  const double fits = c.particles.dx * std::sqrt(std::max(n * kBytesPerParticle, 1.0) /
                                                 std::max(available - kFixedBytes, 1.0));
  if (n > static_cast<double>(std::numeric_limits<std::int32_t>::max()))
    return PreflightProblem{"particles.dx",
                            "dx = " + num(c.particles.dx) + " gives " + num(n) +
                                " particles, more than the 2^31 - 1 the engine can index; "
                                "expected a larger dx (about " +
                                num(c.particles.dx * std::sqrt(n / 2.0e9)) + " or more)",
                            false};
  if (need > available)
    return PreflightProblem{"particles.dx",
                            "dx = " + num(c.particles.dx) + " gives " + num(n) +
                                " particles, which need about " + bytes_text(need) +
                                " of memory; this machine has " + bytes_text(available) +
                                " available: expected dx of about " + num(fits) + " or more",
                            false};
  return std::nullopt;
}

// A fixed time.dt above the largest step the engine's own limits allow at the largest
// allowed time.cfl (1), time.viscous_number and time.diffusion_number (0.25): known unstable.
std::optional<PreflightProblem> check_fixed_dt(const Case& c) {
  if (!(c.time.dt > 0.0) && !(c.time.dt_factor > 0.0)) return std::nullopt;
  const double dt = time_step_limits(c).chosen;
  const char* key = c.time.dt > 0.0 ? "time.dt" : "time.dt_factor";
  Case edge = c;
  edge.time.dt = 0.0;
  edge.time.dt_factor = 0.0;
  edge.time.species_subcycling = false;  // a fixed dt is never sub-cycled
  edge.time.cfl = 1.0;
  edge.time.viscous_number = 0.25;
  edge.time.diffusion_number = 0.25;
  const TimeStepLimits l = time_step_limits(edge);
  if (dt <= l.chosen * (1.0 + 1e-12)) return std::nullopt;
  return PreflightProblem{
      key,
      "expected a fixed step of at most " + num(l.chosen) + " s, the " + l.binding +
          " limit at its largest allowed number (time.cfl = 1, time.viscous_number = "
          "time.diffusion_number = 0.25), got " +
          num(dt) + " s: the run would blow up (use --force to run it anyway)",
      true};
}

// The species with the largest D, which sets the explicit diffusion limit: its D key as
// the case file spells it ("species.D", or "species[s].D" in a [[species]] network).
std::pair<std::string, double> fastest_diffusion(const Case& c) {
  int fastest = 0;
  for (int s = 1; s < c.species_count(); ++s)
    if (c.species_at(s).D > c.species_at(fastest).D) fastest = s;
  const std::string key =
      c.more_species.empty() ? "species.D" : "species[" + std::to_string(fastest) + "].D";
  return {key, c.species_at(fastest).D};
}

// Steps of one pass of the fluid through the channel: a step so small that the run could
// never get anywhere is refused instead of left to hang.
std::optional<PreflightProblem> check_cost(const Case& c) {
  const TimeStepLimits l = time_step_limits(c);
  const auto [d_key, d_max] = fastest_diffusion(c);
  if (l.diffusion > 0.0 && l.diffusion_stages > 1) {
    const double flow = l.chosen, ratio = flow / l.diffusion;
    if (ratio > kMaxDiffusionRatio)
      return PreflightProblem{d_key,
                              "D = " + num(d_max) + " puts the explicit diffusion limit " +
                                  num(ratio) + " times below the flow's step (at most " +
                                  num(kMaxDiffusionRatio) +
                                  " is planned for): expected a smaller D",
                              false};
  }
  const double pass = c.geometry.length / c.fluid.u_bulk;  // [s] one nominal residence time
  const double steps = pass / l.chosen;
  const double work = channel_particle_estimate(c) * steps *
                      (l.diffusion_stages > 1 ? 1.0 + l.diffusion_stages : 1.0);
  if (!(work <= kMaxParticleStepsPerPass)) {
    const std::string key = l.binding.rfind("viscous", 0) == 0     ? "fluid.nu"
                            : l.binding.rfind("diffusion", 0) == 0 ? d_key
                            : l.binding.rfind("fixed", 0) == 0     ? "time.dt"
                                                                   : "particles.dx";
    return PreflightProblem{key,
                            "one pass of the fluid through the channel (L / u_bulk = " + num(pass) +
                                " s) would take " + num(steps) + " steps of " + num(l.chosen) +
                                " s (" + l.binding + " limit), " + num(work) +
                                " particle-steps in all (at most " + num(kMaxParticleStepsPerPass) +
                                " accepted): the run would never end",
                            false};
  }
  return std::nullopt;
}

}  // namespace

double available_memory_bytes() {
  std::ifstream in("/proc/meminfo");
  std::string key;
  double kb = 0.0;
  std::string unit;
  while (in >> key >> kb >> unit)
    if (key == "MemAvailable:") return kb * 1024.0;
  const long pages = ::sysconf(_SC_PHYS_PAGES), page = ::sysconf(_SC_PAGE_SIZE);
  if (pages > 0 && page > 0) return static_cast<double>(pages) * static_cast<double>(page);
  return std::numeric_limits<double>::infinity();
}

std::optional<PreflightProblem> preflight(const Case& c, double available_bytes) {
  if (auto p = check_memory(c, available_bytes)) return p;
  if (auto p = check_fixed_dt(c)) return p;
  return check_cost(c);
}

}  // namespace adrsph::cli
