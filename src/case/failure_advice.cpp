#include "case/failure_advice.hpp"

#include <sstream>

namespace adrsph {

const char* failure_name(FailureKind kind) {
  switch (kind) {
    case FailureKind::none:
      return "";
    case FailureKind::non_finite:
      return "non_finite";
    case FailureKind::speed:
      return "speed";
    case FailureKind::density:
      return "density";
    case FailureKind::concentration:
      return "concentration";
    case FailureKind::lost_particles:
      return "lost_particles";
  }
  return "";
}

namespace {

// The keys that fix the step, as the case sets them.
void fixed_step_advice(std::ostringstream& m, const Case& c, double acoustic_limit) {
  if (c.time.dt > 0)
    m << " or time.dt (now " << c.time.dt << " s, acoustic limit " << acoustic_limit << " s)";
  if (c.time.dt_factor > 0) m << " or time.dt_factor (now " << c.time.dt_factor << ")";
}

}  // namespace

std::string failure_advice(FailureKind kind, const Case& c, double acoustic_limit,
                           bool first_step) {
  std::ostringstream m;
  if (first_step && kind == FailureKind::density && c.particles.jitter > 0) {
    m << "The disordered start is the cause: lower particles.jitter (now " << c.particles.jitter
      << "), or start from the lattice.";
    return m.str();
  }
  switch (kind) {
    case FailureKind::none:
      break;
    case FailureKind::non_finite:
    case FailureKind::speed:
      m << "The time step is above the stable limit for this case: lower time.cfl (now "
        << c.time.cfl << ")";
      fixed_step_advice(m, c, acoustic_limit);
      m << ", or time.diffusion_number (now " << c.time.diffusion_number << ").";
      break;
    case FailureKind::density:
      m << "The flow is too compressible or its step too large: raise fluid.c0_factor (now "
        << c.fluid.c0_factor << ") or lower time.cfl (now " << c.time.cfl << ")";
      fixed_step_advice(m, c, acoustic_limit);
      m << ".";
      break;
    case FailureKind::concentration:
      m << "The species step is above its stable limit: lower time.diffusion_number (now "
        << c.time.diffusion_number << ")";
      fixed_step_advice(m, c, acoustic_limit);
      m << ", or keep time.species_subcycling = true.";
      break;
    case FailureKind::lost_particles:
      m << "The flow near the boundaries is under-resolved or the step too large: lower "
        << "time.cfl (now " << c.time.cfl << ")";
      fixed_step_advice(m, c, acoustic_limit);
      m << ", or keep particles.wall_layers >= 3.";
      break;
  }
  return m.str();
}

}  // namespace adrsph
