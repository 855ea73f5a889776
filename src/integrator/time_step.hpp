// Explicit time-step limits (docs/benchmark.md, section 6):
//   acoustic  dt <= cfl h / (c0 + u_max)       (WCSPH flow)
//   advective dt <= cfl h / u_max              (prescribed flow: no sound waves)
//   viscous   dt <= viscous_number h^2 / nu    (WCSPH flow)
//   diffusion dt <= diffusion_number h^2 / D  (the largest D of the species)
// or a fixed step: time.dt, or time.dt_factor times the smallest of these.
#pragma once

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>

#include "adrsph/case.hpp"
#include "adrsph/simulation.hpp"
#include "species/diffusion_subcycling.hpp"

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
  double D = 0.0;  // the fastest-diffusing species sets the limit
  for (int s = 0; s < c.species_count(); ++s) D = std::max(D, c.species_at(s).D);
  if (D > 0) l.diffusion = c.time.diffusion_number * h * h / D;
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
  // Split the species diffusion off when it alone holds the step down: the flow (or the
  // advection) keeps its own step and diffusion takes one multi-stage RKL2 step within it.
  const bool fixed = c.time.dt > 0 || c.time.dt_factor > 0;
  if (c.time.species_subcycling && !fixed && l.binding == "diffusion") {
    double flow = std::numeric_limits<double>::infinity();
    for (double v : {l.acoustic, l.advective, l.viscous})
      if (v > 0) flow = std::min(flow, v);
    if (std::isfinite(flow)) {
      // RKL2 super-steps within each flow step (diffusion_subcycling.hpp).
      const auto plan = DiffusionSubcycler::plan(std::min(flow / l.diffusion, 1e6));
      l.diffusion_stages = plan.supersteps * plan.stages;  // sparse products per step
      l.chosen = flow;
      std::ostringstream b;
      b << "flow; species diffusion limit " << std::setprecision(3) << flow / l.diffusion
        << "x below it: RKL2, " << plan.supersteps << " x " << plan.stages << " stages";
      l.binding = b.str();
    }
  }
  if (c.time.dt > 0) {
    l.chosen = c.time.dt;
    l.binding = "fixed (time.dt)";
  } else if (c.time.dt_factor > 0) {
    // A fixed multiple of the case's own limit, without sub-cycling: the stability map
    // (docs/robustness.md) steps through it.
    l.chosen *= c.time.dt_factor;
    l.binding = "fixed (time.dt_factor x " + l.binding + ")";
  }
  return l;
}

}  // namespace adrsph
