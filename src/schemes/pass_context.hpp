// What every neighbour pass needs besides the particle arrays: the kernel, the list and the
// constants of the physics, derived once from the case.
#pragma once

#include "kernels/quintic_kernel.hpp"
#include "neighbours/neighbour_list.hpp"
#include "particles/particle_store.hpp"
#include "schemes/shifting.hpp"
#include "schemes/tait_eos.hpp"

namespace adrsph {

struct PhysicsConstants {
  double mass = 0.0;           // m = rho0 dx^2
  double eta2 = 0.0;           // (0.1 h)^2, eqs. (7), (12)
  double four_nu = 0.0;        // 2 (nu_i + nu_j) with uniform nu
  double delta_h_c0_2 = 0.0;   // 2 delta h c0, eq. (8)
  double diffusivity = 0.0;    // D
  TaitEos eos;
  ShiftingVelocity shifting;   // set per step (depends on dt)
};

struct PassContext {
  const QuinticKernel& kernel;
  const NeighbourList& neighbours;
  const PhysicsConstants& phys;
};

}  // namespace adrsph
