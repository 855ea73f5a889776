// Start-up checks of `adrsph run` that need more than the case file: the memory of this
// machine, the cost of the run and the stability of a fixed time step. validate_case()
// (src/case) has already checked every key against its own range; these checks look at the
// keys together, before anything is allocated or written, so that a case that cannot run is
// refused with exit 2 and one line instead of failing later (docs/robustness.md).
#pragma once

#include <optional>
#include <string>

#include "adrsph/case.hpp"

namespace adrsph::cli {

struct PreflightProblem {
  std::string key;      // the case key to change
  std::string message;  // what was found and what is expected
  bool forceable;       // --force runs it anyway (a fixed time.dt above the stable limit)
};

// Upper estimate of the peak memory of a run per particle, and its fixed part: measured peak
// RSS is 600-900 B per particle (docs/results, run.json peak_rss_bytes) above ~14 MB of
// libraries.
inline constexpr double kBytesPerParticle = 1000.0;
inline constexpr double kFixedBytes = 32.0e6;
// Particle-steps that one pass of the fluid through the channel may take: 1e14 is ~300 days
// at the fine case's 4e6 particle-steps/s (perf/README.md), 20,000 times a fine run.
inline constexpr double kMaxParticleStepsPerPass = 1e14;
// Largest ratio of the flow step to the explicit diffusion limit that the RKL2 sub-cycling
// (src/species/diffusion_subcycling.hpp) is planned for.
inline constexpr double kMaxDiffusionRatio = 1e6;

// Bytes of memory available to a new process: MemAvailable of /proc/meminfo, else the
// physical memory; infinity when neither can be read.
double available_memory_bytes();

// The first problem of `c` on a machine with `available_bytes` of memory, or nullopt.
std::optional<PreflightProblem> preflight(const Case& c, double available_bytes);

}  // namespace adrsph::cli
