// The species equation, eq. (12) (docs/benchmark.md, section 3):
//   dC_i/dt = sum_j (m_j rho_i D_i + m_i rho_j D_j)/(rho_i rho_j) (r_ij . grad W)/(r^2+eta^2) (C_i
//   - C_j)
//           + C_i sum_j V_j u_ij . grad_i W_ij          (Lagrangian form of -C div u)
//           - k C_i                                      (integrated exactly, species_decay)
// Optional ALE-consistent term for particles moving with u + du: + du_i . grad C_i.
#pragma once

#include <cmath>

namespace adrsph {

// Diffusion pair term with uniform D: (m_j/rho_j + m_i/rho_i) D lap_weight (C_i - C_j).
// Walls and the outflow buffer take no part (diffusion_mask_j = 0): no flux through the walls or
// the outlet plane, exactly (particle_store.hpp).
// `c_ij` = C_i - C_j (taken in double by the callers).
template <class T>
inline T species_diffusion_pair(T diffusivity, T vol_i, T vol_j, T lap_weight, T c_ij,
                                T diffusion_mask_j) {
  return diffusion_mask_j * diffusivity * (vol_i + vol_j) * lap_weight * c_ij;
}

// Sum of V_j u_ij . grad W_ij; times C_i it is the -C div u term.
template <class T>
inline T species_dilatation_pair(T vol_j, T u_dot_gradw) {
  return vol_j * u_dot_gradw;
}

// First-order reaction over a step, exact: C <- C exp(-k dt).
inline double species_decay(double k, double dt) {
  return std::exp(-k * dt);
}

// Moles exchanged with the inflow/outflow buffers by diffusion (the only species flux
// across the open boundaries besides the particles that cross them), summed over the fluid
// particles: sum_i V_i sum_{j in buffers} diffusion pair term, for the species of
// concentration `c` and diffusivity D. Diagnostic for the species balance; not part of the
// stepping.
struct ParticleStore;
struct PassContext;
double species_buffer_exchange_rate(const ParticleStore& s, const PassContext& ctx, const double* c,
                                    double diffusivity);

}  // namespace adrsph
