// The momentum equation, eqs. (5)-(7): du_i/dt = a_p + a_mu, as pair contributions.
#pragma once

namespace adrsph {

// Pressure gradient, Colagrossi form, eq. (6) with the sign restored (docs/benchmark.md,
// section 2):
//   a_p,i = -(1/rho_i) sum_j V_j (p_i + p_j) grad_i W_ij.
// Returns the scalar s with a_p,i += s * grad_i W_ij.
template <class T>
inline T pressure_gradient_pair(T inv_rho_i, T p_i, T p_j, T vol_j) {
  return -inv_rho_i * vol_j * (p_i + p_j);
}

// Laminar viscosity, eq. (7) in the Morris form that recovers nu lap(u):
//   a_mu,i = sum_j m_j 2 (nu_i + nu_j) / (rho_i + rho_j) (r_ij . grad W_ij) / (r_ij^2 + eta^2) u_ij
// The paper's factor 8 belongs to the Monaghan form (u_ij . r_ij) grad W; with the pair term
// (r_ij . grad W) u_ij it gives 4 nu lap(u), so the factor here is 2 (lattice test:
// tests/test_operators.cpp, ViscousOperatorRecoversNuLaplacian). Uniform nu: 2(nu_i+nu_j) = 4 nu.
// `lap_weight` = (r_ij . grad W_ij) / (r_ij^2 + eta^2), `inv_rho_sum` = 1 / (rho_i + rho_j).
// Returns s with a_mu,i += s * u_ij.
template <class T>
inline T viscous_pair(T mass, T four_nu, T inv_rho_sum, T lap_weight) {
  return mass * four_nu * inv_rho_sum * lap_weight;
}

}  // namespace adrsph
