// Explicit time-step limits (spec section 6):
//   acoustic  dt <= cfl h / (c0 + u_max)       (WCSPH flow)
//   advective dt <= cfl h / u_max              (prescribed flow: no sound waves)
//   viscous   dt <= viscous_number h^2 / nu    (WCSPH flow)
//   diffusion dt <= diffusion_number h^2 / D
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "adrsph/case.hpp"
#include "adrsph/simulation.hpp"

namespace adrsph {

inline TimeStepLimits time_step_limits(const Case& c) {
  TimeStepLimits l;
  const double h = c.h();
  if (c.flow == Flow::wcsph) {
    l.acoustic = c.time.cfl * h / (c.c0() + c.u_max());
    l.viscous = c.time.viscous_number * h * h / c.fluid.nu;
  } else {
    l.advective = c.time.cfl * h / c.u_max();
  }
  if (c.species.D > 0) l.diffusion = c.time.diffusion_number * h * h / c.species.D;
  double best = std::numeric_limits<double>::infinity();
  auto consider = [&](double v, const char* name) {
    if (v > 0 && v < best) {
      best = v;
      l.binding = name;
    }
  };
  consider(l.acoustic, "acoustic");
  consider(l.advective, "advective");
  consider(l.viscous, "viscous");
  consider(l.diffusion, "diffusion");
  l.chosen = best;
  // Sub-cycle the species diffusion when it alone holds the step down: the flow (or the
  // advection) keeps its own step and diffusion takes n sub-steps within it.
  if (c.time.species_subcycling && c.time.dt == 0 && l.binding == "diffusion") {
    double flow = std::numeric_limits<double>::infinity();
    for (double v : {l.acoustic, l.advective, l.viscous})
      if (v > 0) flow = std::min(flow, v);
    if (std::isfinite(flow)) {
      const double n = std::ceil(flow / l.diffusion * (1.0 - 1e-12));
      l.species_substeps = static_cast<int>(std::min(n, 1e9));  // (per full step; see sph_solver)
      l.chosen = flow;
      l.binding = "flow, species diffusion sub-cycled " + std::to_string(l.species_substeps) + "x";
    }
  }
  if (c.time.dt > 0) {
    l.chosen = c.time.dt;
    l.binding = "fixed (time.dt)";
  }
  return l;
}

}  // namespace adrsph
