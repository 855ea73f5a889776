// The fused force pass: one loop over each fluid particle's neighbours computes, as the
// scheme needs them, the momentum rate (eqs. 6-7), the continuity rate with density
// diffusion (eq. 8), the shifting velocity (eq. 10) and the species rate (eq. 12).
// Gather form: each thread writes only its own particle i; no atomics.
#pragma once

#include <cmath>

#include "schemes/continuity.hpp"
#include "schemes/momentum.hpp"
#include "schemes/pass_context.hpp"
#include "species/species_rate.hpp"

namespace adrsph {

// Diffuse = false leaves the species diffusion to the sub-cycler (diffusion_subcycling.hpp).
template <class Scheme, bool Ale, bool Diffuse = true>
void interaction_pass(ParticleStore& s, const PassContext& ctx) {
  const std::size_t n = s.size();
  const double* x = s.x.data();
  const double* y = s.y.data();
  const double* vx = s.vx.data();
  const double* vy = s.vy.data();
  const double* rho = s.rho.data();
  const double* p = s.p.data();
  const double* vol = s.vol.data();
  const double* c = s.c.data();
  const double* cm = s.c_mask.data();
  const std::uint32_t* nb = ctx.neighbours.data();
  const QuinticKernel& kernel = ctx.kernel;
  const PhysicsConstants& ph = ctx.phys;
  const double eta2 = ph.eta2, mass = ph.mass, four_nu = ph.four_nu, dh = ph.delta_h_c0_2;
  const double diffusivity = ph.diffusivity;

#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    if (s.kind[i] != static_cast<std::uint8_t>(Kind::fluid)) continue;
    const double xi = x[i], yi = y[i], vxi = vx[i], vyi = vy[i];
    const double rhoi = rho[i], pi = p[i], voli = vol[i], ci = c[i];
    const double inv_rhoi = 1.0 / rhoi;
    double ax = 0, ay = 0, drho = 0, gx = 0, gy = 0;     // flow
    double cdiff = 0, cdil = 0, cgx = 0, cgy = 0;         // species
#pragma omp simd reduction(+ : ax, ay, drho, gx, gy, cdiff, cdil, cgx, cgy)
    for (std::uint32_t k = ctx.neighbours.begin(i); k < ctx.neighbours.end(i); ++k) {
      const std::uint32_t j = nb[k];
      const double dx = xi - x[j], dy = yi - y[j];
      const double r2 = dx * dx + dy * dy;
      const double r = std::sqrt(r2) + 1e-30;
      // One division gives 1/r, 1/(r^2 + eta^2) and 1/(rho_i + rho_j): divisions and the
      // square root are the slowest operations of the pair (performance-notes).
      const double reg = r2 + eta2;
      const double rho_sum = Scheme::momentum ? rhoi + rho[j] : 1.0;
      const double inv = 1.0 / (r * reg * rho_sum);
      const double dwdr = kernel.derivative(r);
      const double f = dwdr * inv * reg * rho_sum;          // (dW/dr) / r
      const double gwx = f * dx, gwy = f * dy;               // grad_i W_ij
      const double lap_weight = dwdr * r2 * inv * rho_sum;   // (r_ij . grad W_ij) / (r_ij^2 + eta^2)
      const double volj = vol[j];
      const double uxij = vxi - vx[j], uyij = vyi - vy[j];
      const double u_dot_gradw = uxij * gwx + uyij * gwy;
      if constexpr (Scheme::momentum) {
        const double sp = pressure_gradient_pair(inv_rhoi, pi, p[j], volj);
        const double sv = viscous_pair(mass, four_nu, r * reg * inv, lap_weight);
        ax += sp * gwx + sv * uxij;
        ay += sp * gwy + sv * uyij;
        cdil += species_dilatation_pair(volj, u_dot_gradw);
      }
      if constexpr (Scheme::continuity) {
        drho += continuity_pair(rhoi, volj, u_dot_gradw) +
                density_diffusion_pair(dh, volj, rhoi, rho[j], lap_weight);
      }
      if constexpr (Scheme::shifting) {
        gx += volj * gwx;
        gy += volj * gwy;
      }
      if constexpr (Diffuse)
        cdiff += species_diffusion_pair(diffusivity, voli, volj, lap_weight, ci, c[j], cm[j]);
      if constexpr (Ale && Scheme::shifting) {
        const double dc = cm[j] * volj * (c[j] - ci);  // grad C_i = sum_j V_j (C_j - C_i) grad W
        cgx += dc * gwx;
        cgy += dc * gwy;
      }
    }
    if constexpr (Scheme::momentum) {
      s.ax[i] = ax;
      s.ay[i] = ay;
    }
    if constexpr (Scheme::continuity) s.drho[i] = drho;
    double dci = cdiff + ci * cdil;
    if constexpr (Scheme::shifting) {
      double sxi, syi;
      ph.shifting(gx, gy, sxi, syi);
      s.sx[i] = sxi;
      s.sy[i] = syi;
      if constexpr (Ale) dci += sxi * cgx + syi * cgy;  // du_i . grad C_i
    }
    s.dc[i] = dci;
  }
}

}  // namespace adrsph
