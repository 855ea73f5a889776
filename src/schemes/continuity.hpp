// Density evolution of the modern scheme, eq. (8):
//   d rho_i/dt = rho_i sum_j V_j (u_i - u_j) . grad_i W_ij + delta h D_i
// with the Ferrari / Molteni-Colagrossi density diffusion D_i = c0 lap(rho)_i,
//   lap(f)_i = 2 sum_j V_j (f_i - f_j) (r_ij . grad W_ij) / (r_ij^2 + eta^2).
#pragma once

namespace adrsph {

// rho_i V_j u_ij . grad W_ij
template <class T>
inline T continuity_pair(T rho_i, T vol_j, T u_dot_gradw) {
  return rho_i * vol_j * u_dot_gradw;
}

// delta h c0 * 2 V_j (rho_i - rho_j) lap_weight; `delta_h_c0_2` = 2 delta h c0.
// (rho_ij = rho_i - rho_j, taken in double by the caller: the differences are ~1e-4 rho.)
template <class T>
inline T density_diffusion_pair(T delta_h_c0_2, T vol_j, T rho_ij, T lap_weight) {
  return delta_h_c0_2 * vol_j * rho_ij * lap_weight;
}

}  // namespace adrsph
