// Density and pressure of the fluid particles before the force pass.
#pragma once

#include "schemes/pass_context.hpp"

namespace adrsph {

// Conventional scheme: rho_i = m sum_j W_ij (self included), eq. (3) with W for the printed
// grad W (docs/benchmark.md, section 2), then p_i and V_i as fluid_pressure() does. Fluid
// particles only. `predicted`: the sums the previous force pass took at these very positions
// (pass_context.hpp, DensityPrediction), used where present (not NaN) instead of a neighbour
// loop; the same numbers, bit for bit, at a fraction of the cost.
void summation_density(ParticleStore& s, const PassContext& ctx, const float* predicted = nullptr);

// p_i = Tait(rho_i) (+ p_b), eq. (2), and V_i = m / rho_i. Fluid particles only (the boundary
// pass sets both for the others).
void fluid_pressure(ParticleStore& s, const TaitEos& eos, double mass);

}  // namespace adrsph
