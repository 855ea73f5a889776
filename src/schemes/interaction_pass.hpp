// The fused force pass: one loop over each fluid particle's neighbours computes, as the
// scheme needs them, the momentum rate (eqs. 6-7), the continuity rate with density
// diffusion (eq. 8), the shifting velocity (eq. 10) and the species rate (eq. 12).
// Gather form: each thread writes only its own particle i; no atomics.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

#include "schemes/continuity.hpp"
#include "schemes/momentum.hpp"
#include "schemes/pass_context.hpp"
#include "species/species_rate.hpp"

namespace adrsph {

// Diffuse = false leaves the species diffusion to the sub-cycler (diffusion_subcycling.hpp).
// Network = true also gives the second and later species of a network (ParticleStore::c_more)
// their eq. (12) rates in the same neighbour walk: each has its own D, and shares the pair
// weights and the -C div u sum with the first. It sums for ParticleStore::kMaxMore of them
// whatever the case has (the spare sums read the first species and are dropped), so one
// instantiation serves every network; a case of one species runs Network = false, the loop
// it always had.
//
// Pair arithmetic in single precision (`real`): the kernel, its gradient and every pair
// term run 8 lanes wide instead of 4 (perf/README.md, "float pair arithmetic"). Whatever
// would lose digits in float is taken in double first and then rounded: the separation
// r_i - r_j (positions are ~1e5 dx from the origin), u_i - u_j and C_i - C_j (neighbour
// differences are ~1e-4 of the values). Densities enter as rho - rho0 (ParticleStore::
// rho_excess, ~1e-2 rho0 at most), whose float difference keeps what the double one would. The sums
// of ~35 pair terms are float too; their rounding (~1e-7 relative) is far below the scheme's own
// pair-sum errors.
//
// Neighbours: NeighbourList::Offsets or ::Indices (interaction_pass below picks the list's).
template <class Scheme, bool Ale, bool Diffuse, bool Network, class Neighbours>
void interaction_pass_with(ParticleStore& s, const PassContext& ctx, const Neighbours form) {
  static_assert(!(Ale && Network), "the ALE term is written for one species");
  static_assert(ParticleStore::kMaxMore == 3, "the network sums below are written for three");
  using real = float;
  const std::size_t n = s.size();
  const double* x = s.x.data();
  const double* y = s.y.data();
  const double* vx = s.vx.data();
  const double* vy = s.vy.data();
  const double* rho = s.rho.data();
  const float* rho_excess = s.rho_excess.data();  // rho - rho0: a float gather, not a double one
  const float* p = s.p.data();
  const float* vol = s.vol.data();
  const double* c = s.c.data();
  const float* dmask = s.diffusion_mask.data();
  const float* fside = s.fluid_side.data();
  // Local copies: the stores of the rates below may alias references, and g++ then reloads
  // them inside the loops (2x slower, measured on the summation density).
  const QuinticKernel kernel = ctx.kernel;
  const PhysicsConstants& ph = ctx.phys;
  const real eta2 = static_cast<real>(ph.eta2), mass = static_cast<real>(s.mass);
  const real two_rho0 = static_cast<real>(2.0 * ph.eos.rho0);
  const real four_nu = static_cast<real>(ph.four_nu), dh = static_cast<real>(ph.delta_h_c0_2);
  const real diffusivity = static_cast<real>(ph.diffusivity);
  [[maybe_unused]] const real body_force = static_cast<real>(ph.body_force_x);
  // The network's other species (unused slots read c with D = 0, and are not stored).
  const int more = s.needs().more_species;
  auto more_c = [&](int e) { return e < more ? s.c_more[e].data() : c; };
  const double *c1 = more_c(0), *c2 = more_c(1), *c3 = more_c(2);
  const real d1 = static_cast<real>(ph.more_diffusivity[0]),
             d2 = static_cast<real>(ph.more_diffusivity[1]),
             d3 = static_cast<real>(ph.more_diffusivity[2]);
  // Conventional scheme: the summation density at the next positions (pass_context.hpp).
  constexpr bool kPredict = Scheme::summation_density;
  const DensityPrediction next = ctx.next_density;
  const float* ddx = next.dx;
  const float* ddy = next.dy;

#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    if (s.kind[i] != kFluidByte) {
      // Buffers do not shift; a particle that enters the fluid at the end of this step is
      // then checked (check_state) with a defined zero, not a stale value of its index.
      if constexpr (Scheme::shifting) s.sx[i] = s.sy[i] = 0.0f;
      // No prediction for buffers: one that becomes fluid gets its own sum (NaN says so).
      if constexpr (kPredict) next.sum[i] = std::numeric_limits<float>::quiet_NaN();
      continue;
    }
    const double xi = x[i], yi = y[i], vxi = vx[i], vyi = vy[i], rhoi_d = rho[i], ci_d = c[i];
    const real rhoi = static_cast<real>(rhoi_d), pi = p[i], voli = vol[i];
    const real inv_rhoi = real(1) / rhoi;
    const real excess_i = Scheme::momentum ? rho_excess[i] : real(0);
    real ax = 0, ay = 0, drho = 0, gx = 0, gy = 0;  // flow
    real cdiff = 0, cdil = 0, cgx = 0, cgy = 0;     // species
    real wsum = 0;                                  // density at the next positions
    real cd1 = 0, cd2 = 0, cd3 = 0;                 // diffusion of the network's others
    const double c1i = Network ? c1[i] : 0.0, c2i = Network ? c2[i] : 0.0,
                 c3i = Network ? c3[i] : 0.0;
    const real ddxi = kPredict ? ddx[i] : real(0), ddyi = kPredict ? ddy[i] : real(0);
    std::uint32_t row_buffer[NeighbourList::kRowBuffer];
    const NeighbourList::Row row = ctx.neighbours.row_of(form, i, row_buffer);
#pragma omp simd reduction(+ : ax, ay, drho, gx, gy, cdiff, cdil, cgx, cgy, wsum, cd1, cd2, cd3)
    for (std::uint32_t k = 0; k < row.whole; ++k) {
      const std::uint32_t j = row.index[k];
      const real dx = static_cast<real>(xi - x[j]), dy = static_cast<real>(yi - y[j]);
      const real r2 = dx * dx + dy * dy;
      const real r = std::sqrt(r2) + real(1e-30);
      // One division gives 1/r, 1/(r^2 + eta^2) and 1/(rho_i + rho_j): divisions and the
      // square root are the slowest operations of the pair (perf/README.md, "Build flags").
      const real reg = r2 + eta2;
      const real rho_sum = Scheme::momentum ? two_rho0 + (excess_i + rho_excess[j]) : real(1);
      const real inv = real(1) / (r * reg * rho_sum);
      const real dwdr = kernel.derivative<real>(r);
      const real f = dwdr * inv * reg * rho_sum;  // (dW/dr) / r
      const real gwx = f * dx, gwy = f * dy;      // grad_i W_ij
      const real lap_weight = QuinticKernel::laplacian_weight_shared(dwdr, r2, inv, rho_sum);
      const real volj = vol[j];
      const real uxij = static_cast<real>(vxi - vx[j]), uyij = static_cast<real>(vyi - vy[j]);
      const real u_dot_gradw = uxij * gwx + uyij * gwy;
      if constexpr (Scheme::momentum) {
        const real sp = pressure_gradient_pair(inv_rhoi, pi, p[j], volj);
        const real sv = viscous_pair(mass, four_nu, r * reg * inv, lap_weight);
        ax += sp * gwx + sv * uxij;
        ay += sp * gwy + sv * uyij;
      }
      if constexpr (Scheme::dilatation) cdil += species_dilatation_pair(volj, u_dot_gradw);
      if constexpr (Scheme::continuity) {
        const real rho_ij = excess_i - rho_excess[j];
        drho += continuity_pair(rhoi, volj, u_dot_gradw) +
                density_diffusion_pair(dh, volj, rho_ij, lap_weight);
      }
      if constexpr (Scheme::shifting) {
        gx += volj * gwx;
        gy += volj * gwy;
      }
      if constexpr (kPredict) {
        const real nx = dx + (ddxi - ddx[j]), ny = dy + (ddyi - ddy[j]);
        wsum += kernel.value<real>(std::sqrt(nx * nx + ny * ny));
      }
      const real c_ji = static_cast<real>(c[j] - ci_d);
      if constexpr (Diffuse)
        cdiff += species_diffusion_pair(diffusivity, voli, volj, lap_weight, -c_ji, dmask[j]);
      if constexpr (Diffuse && Network) {
        const real m = dmask[j];
        cd1 += species_diffusion_pair(d1, voli, volj, lap_weight, real(c1i - c1[j]), m);
        cd2 += species_diffusion_pair(d2, voli, volj, lap_weight, real(c2i - c2[j]), m);
        cd3 += species_diffusion_pair(d3, voli, volj, lap_weight, real(c3i - c3[j]), m);
      }
      if constexpr (Ale && Scheme::shifting) {
        // grad C_i = sum_j V_j (C_j - C_i) grad W over the particles that carry species:
        // fluid, inflow buffer (diffusion_mask) and outflow buffer (fluid_side).
        const real dc = std::max(dmask[j], fside[j]) * volj * c_ji;
        cgx += dc * gwx;
        cgy += dc * gwy;
      }
    }
    if constexpr (Scheme::momentum) {
      s.ax[i] = ax + body_force;  // eq. (5), plus the driving body force (pass_context.hpp)
      s.ay[i] = ay;
    }
    if constexpr (Scheme::continuity) s.drho[i] = drho;
    if constexpr (kPredict) next.sum[i] = wsum;
    double dci = double(cdiff) + ci_d * double(cdil);
    if constexpr (Scheme::shifting) {
      double sxi, syi;
      ph.shifting(gx, gy, sxi, syi);
      s.sx[i] = static_cast<float>(sxi);
      s.sy[i] = static_cast<float>(syi);
      if constexpr (Ale) dci += sxi * cgx + syi * cgy;  // du_i . grad C_i
    }
    s.dc[i] = static_cast<float>(dci);
    if constexpr (Network) {
      const real sums[3] = {cd1, cd2, cd3};
      const double ci_more[3] = {c1i, c2i, c3i};
      for (int e = 0; e < more; ++e)
        s.dc_more[e][i] = static_cast<float>(double(sums[e]) + ci_more[e] * double(cdil));
    }
  }
}

template <class Scheme, bool Ale, bool Diffuse = true, bool Network = false>
void interaction_pass(ParticleStore& s, const PassContext& ctx) {
  ctx.neighbours.with_indices(
      [&](auto form) { interaction_pass_with<Scheme, Ale, Diffuse, Network>(s, ctx, form); });
}

}  // namespace adrsph
