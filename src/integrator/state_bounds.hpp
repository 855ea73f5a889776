// What the guards of a step read of the new state (step_guards.cpp, docs/robustness.md): per
// particle, whether its values are finite, its speed, its transport speed, its density
// deviation and how far its concentrations are outside [0, c_max]; over the particles, the
// largest of each. Where nothing changes the state after the second stage of the step (no
// sub-cycled diffusion), advance() takes them in its own loop, as it writes each particle;
// otherwise check_state() takes them in a pass of its own after the diffusion.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "particles/particle_store.hpp"

namespace adrsph {

// The largest of each guarded quantity over the particles (walls excluded); `bad` counts the
// particles with a non-finite value.
struct StateBounds {
  double vmax2 = 0.0, tmax2 = 0.0, drho_max = 0.0, c_dev = 0.0;
  int bad = 0;
};

// The constants of one step's guards, and the terms of one particle.
struct StateProbe {
  double c_max = 0.0;  // the concentration band's top (every species of a network together)
  double rho0 = 1.0;
  int more = 0;           // the network's other species in use
  bool shifting = false;  // sx, sy exist (a shifting scheme)

  // |transport velocity|^2 of particle i: how far it moves (u + du for a shifting scheme's
  // fluid particles, u otherwise).
  double transport_speed2(const ParticleStore& s, std::size_t i) const {
    const bool shifts = shifting && s.kind[i] == kFluidByte;
    const double tx = s.vx[i] + (shifts ? s.sx[i] : 0.0);
    const double ty = s.vy[i] + (shifts ? s.sy[i] : 0.0);
    return tx * tx + ty * ty;
  }
  // The largest distance of particle i's C (any species) outside [0, c_max]; NaN if not finite.
  double c_outside(const ParticleStore& s, std::size_t i) const {
    double d = std::max(s.c[i] - c_max, -s.c[i]);
    for (int e = 0; e < more; ++e) d = std::max({d, s.c_more[e][i] - c_max, -s.c_more[e][i]});
    for (int e = 0; e < more; ++e)
      if (!std::isfinite(s.c_more[e][i])) return std::nan("");
    return d;
  }
  // Every value the guards read of particle i is finite (t2: its transport_speed2).
  static bool finite_state(const ParticleStore& s, std::size_t i, double t2) {
    return std::isfinite(s.x[i]) && std::isfinite(s.y[i]) && std::isfinite(t2) &&
           std::isfinite(s.rho[i]) && std::isfinite(s.c[i]);
  }
  // Particle i (not a wall) into the running maxima (the reduction variables of a loop).
  void add(const ParticleStore& s, std::size_t i, double& vmax2, double& tmax2, double& drho_max,
           double& c_dev, int& bad) const {
    const double v2 = s.vx[i] * s.vx[i] + s.vy[i] * s.vy[i];  // fluid velocity (Mach check)
    const double t2 = transport_speed2(s, i);
    const double c_off = more > 0 ? c_outside(s, i) : std::max(s.c[i] - c_max, -s.c[i]);
    const bool finite = finite_state(s, i, t2) && std::isfinite(c_off);
    bad += finite ? 0 : 1;
    vmax2 = std::max(vmax2, finite ? v2 : 0.0);
    tmax2 = std::max(tmax2, finite ? t2 : 0.0);
    drho_max = std::max(drho_max, finite ? std::fabs(s.rho[i] / rho0 - 1.0) : 0.0);
    if (finite) c_dev = std::max(c_dev, c_off);
  }
};

}  // namespace adrsph
