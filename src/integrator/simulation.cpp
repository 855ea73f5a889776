// Placeholder until the SPH integrator lands.
#include "adrsph/simulation.hpp"

namespace adrsph {
RunResult run_simulation(const Case&, RunObserver&) {
  RunResult r;
  r.status = "failed";
  r.message = "SPH integrator not implemented yet";
  return r;
}
}  // namespace adrsph
