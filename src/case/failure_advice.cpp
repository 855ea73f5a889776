#include "case/failure_advice.hpp"

#include <sstream>

namespace adrsph {

std::string failure_advice(FailureKind kind, const Case& c, double acoustic_limit) {
  std::ostringstream m;
  switch (kind) {
    case FailureKind::none:
      break;
    case FailureKind::unstable_step:
      m << "The time step is above the stable limit for this case: lower time.cfl (now "
        << c.time.cfl << ")";
      if (c.time.dt > 0)
        m << " or time.dt (now " << c.time.dt << " s, limit " << acoustic_limit << " s)";
      m << ", or time.diffusion_number (now " << c.time.diffusion_number << ").";
      break;
    case FailureKind::lost_particles:
      m << "The flow near the boundaries is under-resolved or the step too large: lower "
        << "time.cfl (now " << c.time.cfl << ") or keep particles.wall_layers >= 3.";
      break;
  }
  return m.str();
}

}  // namespace adrsph
