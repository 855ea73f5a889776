// Explicit time-step limits (spec section 6):
//   acoustic  dt <= cfl h / (c0 + u_max)       (WCSPH flow)
//   advective dt <= cfl h / u_max              (prescribed flow: no sound waves)
//   viscous   dt <= viscous_number h^2 / nu    (WCSPH flow)
//   diffusion dt <= diffusion_number h^2 / D
#pragma once

#include <algorithm>
#include <limits>

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
  if (c.time.dt > 0) {
    l.chosen = c.time.dt;
    l.binding = "fixed (time.dt)";
  }
  return l;
}

}  // namespace adrsph
