// What every neighbour pass needs besides the particle arrays: the kernel, the list and the
// constants of the physics, derived once from the case.
#pragma once

#include <array>

#include "kernels/quintic_kernel.hpp"
#include "neighbours/neighbour_list.hpp"
#include "particles/particle_store.hpp"
#include "schemes/shifting.hpp"
#include "schemes/tait_eos.hpp"

namespace adrsph {

struct PhysicsConstants {
  double eta2 = 0.0;          // (0.1 h)^2, eqs. (7), (12)
  double four_nu = 0.0;       // 2 (nu_i + nu_j) with uniform nu
  double delta_h_c0_2 = 0.0;  // 2 delta h c0, eq. (8)
  double diffusivity = 0.0;   // D (of the first species)
  // D of the second and later species of a network (ParticleStore::c_more), and the largest
  // D of all (the sub-cycled diffusion's weights and its step limit).
  std::array<double, ParticleStore::kMaxMore> more_diffusivity{};
  double max_diffusivity = 0.0;
  // Walls at y = +-wall_image_y mirror the species in the diffusion sum (particles.wall_images,
  // species/wall_images.hpp); 0: the walls are only skipped.
  double wall_image_y = 0.0;
  // Body force per mass along x on the fluid [mm/s^2] (fluid.driving = "body_force"), 0 else.
  double body_force_x = 0.0;
  TaitEos eos;
  ShiftingVelocity shifting;  // set per step (depends on dt): set_step

  // The constants that depend on the step dt: the shifting coefficient eps h^2 / dt and its
  // cap shift_max dx / dt (eq. (10)). The solver sets them at every step; a test or benchmark
  // that runs a pass on its own sets them for the step it imitates.
  void set_step(const Case& c, double dt) {
    shifting.coefficient = c.modern.shift_eps * c.h() * c.h() / dt;
    shifting.max_speed = c.modern.shift_max * c.particles.dx / dt;
  }
};

// Conventional scheme: the force pass also sums the kernel at the positions the integrator
// will give the particles next, x_next = x + d with d the displacement of the coming stage
// (0 for walls), so that the next evaluation needs no summation-density pass of its own
// (density_passes.hpp). The pair separation is r_ij + d_i - d_j, in single precision like
// the rest of the pair arithmetic (its rounding, ~1e-7 of r, is that of the pass itself).
struct DensityPrediction {
  float* sum = nullptr;       // out: sum_j W(x_next_i - x_next_j) per fluid i; NaN for the others
  const float* dx = nullptr;  // d per particle
  const float* dy = nullptr;
};

struct PassContext {
  const QuinticKernel& kernel;
  const NeighbourList& neighbours;
  const PhysicsConstants& phys;
  DensityPrediction next_density = {};
};

}  // namespace adrsph
