// Density and pressure of the fluid particles before the force pass.
#pragma once

#include "schemes/pass_context.hpp"

namespace adrsph {

// Conventional scheme: rho_i = m sum_j W_ij (self included), eq. (3) with W for the printed
// grad W (spec section 2). Fluid particles only.
void summation_density(ParticleStore& s, const PassContext& ctx);

// p_i = Tait(rho_i) (+ p_b), eq. (2). Fluid particles only.
void fluid_pressure(ParticleStore& s, const TaitEos& eos);

// V = m / rho for every particle.
void particle_volumes(ParticleStore& s, double mass);

}  // namespace adrsph
