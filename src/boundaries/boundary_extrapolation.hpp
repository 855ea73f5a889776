// Dummy-particle walls and open-boundary buffers get their pressure from the fluid
// (generalised wall boundary of Adami et al. 2012, no body force):
//   p_w = sum_f p_f W_wf / sum_f W_wf,  rho_w = Tait^-1(p_w),
//   u_w = -sum_f u_f W_wf / sum_f W_wf   (no slip: 2 u_wall - u~ with u_wall = 0).
// Inlet buffer particles take p and rho the same way (zero pressure gradient at the inlet),
// keeping their prescribed velocity. Every one of them also gets V = m / rho. Outlet buffer
// particles carry the reference pressure (p = p_b, rho = rho0) and their frozen velocity; the
// density pass before this one sets that state (density_passes.hpp, outflow_state).
#pragma once

#include "schemes/pass_context.hpp"

namespace adrsph {

void extrapolate_to_boundaries(ParticleStore& s, const PassContext& ctx);

}  // namespace adrsph
