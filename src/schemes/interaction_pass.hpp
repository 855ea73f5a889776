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
#include "schemes/pair_records.hpp"
#include "schemes/pass_context.hpp"
#include "schemes/simd8.hpp"
#include "species/species_rate.hpp"

namespace adrsph {

// Diffuse = false leaves the species diffusion to the sub-cycler (diffusion_subcycling.hpp).
// Network = true also gives the second and later species of a network (ParticleStore::c_more)
// their eq. (12) rates in the same neighbour walk: each has its own D, and shares the pair
// weights and the -C div u sum with the first. It sums for ParticleStore::kMaxMore of them
// whatever the case has (the spare sums difference zeros with D = 0, and are not stored), so
// one instantiation serves every network; a case of one species runs Network = false.
//
// Pair arithmetic in single precision, eight pairs at once (V: simd8.hpp). What a neighbour
// contributes is read from its record (pair_records.hpp): eight records are loaded whole and
// transposed, one vector per field. The differences that would lose digits in float (the
// separation r_i - r_j, u_i - u_j and C_i - C_j: neighbour differences are ~1e-4 of the
// values) are taken from the records' hi and lo parts and rounded once, as the difference of
// the doubles would be. Densities enter as rho - rho0 in float (~1e-2 rho0 at most), whose
// float difference keeps what the double one would. The sums of ~35 pair terms
// are float too; their rounding (~1e-7 relative) is far below the scheme's own pair-sum errors
// (tests/test_fused_pass.cpp holds them to the same sums in double).
//
// Neighbours: NeighbourList::Offsets or ::Indices (interaction_pass below picks the list's).
// `records`: filled for this state by the caller (interaction_pass below).
template <class Scheme, bool Ale, bool Diffuse, bool Network, class V, class Neighbours>
void interaction_pass_with(ParticleStore& s, const PassContext& ctx, const float* records,
                           const Neighbours form) {
  static_assert(!(Ale && Network), "the ALE term is written for one species");
  static_assert(ParticleStore::kMaxMore == 3, "the network sums below are written for three");
  using L = RecordLayout<Scheme::momentum, Network>;
  constexpr int kFields = L::fields;
  const std::size_t n = s.size();
  // Local copies: the stores of the rates below may alias references, and g++ then reloads
  // them inside the loops (2x slower, measured on the summation density).
  const QuinticKernel kernel = ctx.kernel;
  const PhysicsConstants& ph = ctx.phys;
  const V eta2 = static_cast<float>(ph.eta2), mass = static_cast<float>(s.mass);
  const V two_rho0 = static_cast<float>(2.0 * ph.eos.rho0);
  const V four_nu = static_cast<float>(ph.four_nu), dh = static_cast<float>(ph.delta_h_c0_2);
  const V diffusivity = static_cast<float>(ph.diffusivity);
  [[maybe_unused]] const float body_force = static_cast<float>(ph.body_force_x);
  // The network's other species (unused slots difference zeros with D = 0, and are not stored).
  const int more = s.needs().more_species;
  const V d1 = static_cast<float>(ph.more_diffusivity[0]),
          d2 = static_cast<float>(ph.more_diffusivity[1]),
          d3 = static_cast<float>(ph.more_diffusivity[2]);
  // Conventional scheme: the summation density at the next positions (pass_context.hpp); the
  // displacement d is the records' extra0, extra1.
  constexpr bool kPredict = Scheme::summation_density;
  const DensityPrediction next = ctx.next_density;

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
    const float* ri = records + i * kFields;
    const V x_hi = ri[L::x_hi], y_hi = ri[L::y_hi], x_lo = ri[L::x_lo], y_lo = ri[L::y_lo];
    const V c_hi = ri[L::c_hi], c_lo = ri[L::c_lo];
    const double ci_d = s.c[i];
    const float rhoi_f = static_cast<float>(s.rho[i]);
    const V rhoi = rhoi_f, voli = ri[L::vol];
    V ux_hi = 0.0f, uy_hi = 0.0f, ux_lo = 0.0f, uy_lo = 0.0f, pi = 0.0f, excess_i = 0.0f;
    if constexpr (Scheme::momentum) {
      ux_hi = ri[L::vx_hi], uy_hi = ri[L::vy_hi], ux_lo = ri[L::vx_lo], uy_lo = ri[L::vy_lo];
      pi = ri[L::p], excess_i = ri[L::rho_excess];
    }
    const V inv_rhoi = 1.0f / rhoi_f;
    const V ddxi = kPredict ? ri[L::extra0] : 0.0f, ddyi = kPredict ? ri[L::extra1] : 0.0f;
    V ax = 0.0f, ay = 0.0f, drho = 0.0f, gx = 0.0f, gy = 0.0f;  // flow
    V cdiff = 0.0f, cdil = 0.0f, cgx = 0.0f, cgy = 0.0f;        // species
    V wsum = 0.0f;                                              // density at the next positions
    V cd1 = 0.0f, cd2 = 0.0f, cd3 = 0.0f;                       // diffusion of the network's others
    V c1_hi = 0.0f, c1_lo = 0.0f, c2_hi = 0.0f, c2_lo = 0.0f, c3_hi = 0.0f, c3_lo = 0.0f;
    if constexpr (Network) {
      c1_hi = ri[L::more], c1_lo = ri[L::more + 1], c2_hi = ri[L::more + 2];
      c2_lo = ri[L::more + 3], c3_hi = ri[L::more + 4], c3_lo = ri[L::more + 5];
    }
    std::uint32_t row_buffer[NeighbourList::kRowBuffer];
    const NeighbourList::Row row = ctx.neighbours.row_of(form, i, row_buffer);
    for (std::uint32_t k = 0; k < row.whole; k += NeighbourList::kPad) {
      static_assert(NeighbourList::kPad == 8, "a row runs in vectors of eight pairs");
      const float* rows[8];
      for (int m = 0; m < 8; ++m) rows[m] = records + std::size_t(row.index[k + m]) * kFields;
      V f[kFields];  // f[field]: lane m holds that field of neighbour index[k + m]
      for (int block = 0; block < kFields; block += 8) V::transpose(rows, block, f + block);
      const V dx = (x_hi - f[L::x_hi]) + (x_lo - f[L::x_lo]);
      const V dy = (y_hi - f[L::y_hi]) + (y_lo - f[L::y_lo]);
      const V r2 = dx * dx + dy * dy;
      const V r = sqrt(r2) + V(1e-30f);
      // One division gives 1/r, 1/(r^2 + eta^2) and 1/(rho_i + rho_j): divisions and the
      // square root are the slowest operations of the pair (perf/README.md, "Build flags").
      const V reg = r2 + eta2;
      V rho_sum = 1.0f, excess_j = 0.0f, uxij = 0.0f, uyij = 0.0f;
      if constexpr (Scheme::momentum) {
        excess_j = f[L::rho_excess];
        rho_sum = two_rho0 + (excess_i + excess_j);
        uxij = (ux_hi - f[L::vx_hi]) + (ux_lo - f[L::vx_lo]);
        uyij = (uy_hi - f[L::vy_hi]) + (uy_lo - f[L::vy_lo]);
      }
      const V inv = V(1.0f) / (r * reg * rho_sum);
      const V dwdr = kernel.derivative<V>(r);
      const V fr = dwdr * inv * reg * rho_sum;  // (dW/dr) / r
      const V gwx = fr * dx, gwy = fr * dy;     // grad_i W_ij
      const V lap_weight = QuinticKernel::laplacian_weight_shared(dwdr, r2, inv, rho_sum);
      const V volj = f[L::vol];
      const V u_dot_gradw = uxij * gwx + uyij * gwy;
      if constexpr (Scheme::momentum) {
        const V sp = pressure_gradient_pair<V>(inv_rhoi, pi, f[L::p], volj);
        const V sv = viscous_pair<V>(mass, four_nu, r * reg * inv, lap_weight);
        ax += sp * gwx + sv * uxij;
        ay += sp * gwy + sv * uyij;
      }
      if constexpr (Scheme::dilatation) cdil += species_dilatation_pair<V>(volj, u_dot_gradw);
      if constexpr (Scheme::continuity) {
        const V rho_ij = excess_i - excess_j;
        drho += continuity_pair<V>(rhoi, volj, u_dot_gradw) +
                density_diffusion_pair<V>(dh, volj, rho_ij, lap_weight);
      }
      if constexpr (Scheme::shifting) {
        gx += volj * gwx;
        gy += volj * gwy;
      }
      if constexpr (kPredict) {
        const V nx = dx + (ddxi - f[L::extra0]), ny = dy + (ddyi - f[L::extra1]);
        wsum += kernel.value<V>(sqrt(nx * nx + ny * ny));
      }
      const V c_ij = (c_hi - f[L::c_hi]) + (c_lo - f[L::c_lo]);
      const V dmask = f[L::diffusion_mask];
      if constexpr (Diffuse)
        cdiff += species_diffusion_pair<V>(diffusivity, voli, volj, lap_weight, c_ij, dmask);
      if constexpr (Diffuse && Network) {
        const int m = L::more;
        const V c1_ij = (c1_hi - f[m]) + (c1_lo - f[m + 1]);
        const V c2_ij = (c2_hi - f[m + 2]) + (c2_lo - f[m + 3]);
        const V c3_ij = (c3_hi - f[m + 4]) + (c3_lo - f[m + 5]);
        cd1 += species_diffusion_pair<V>(d1, voli, volj, lap_weight, c1_ij, dmask);
        cd2 += species_diffusion_pair<V>(d2, voli, volj, lap_weight, c2_ij, dmask);
        cd3 += species_diffusion_pair<V>(d3, voli, volj, lap_weight, c3_ij, dmask);
      }
      if constexpr (Ale && Scheme::shifting) {
        // grad C_i = sum_j V_j (C_j - C_i) grad W over the particles that carry species:
        // fluid, inflow buffer (diffusion_mask) and outflow buffer (fluid_side, extra0).
        const V dc = -(max(dmask, f[L::extra0]) * volj * c_ij);
        cgx += dc * gwx;
        cgy += dc * gwy;
      }
    }
    if constexpr (Scheme::momentum) {
      s.ax[i] = sum(ax) + body_force;  // eq. (5), plus the driving body force (pass_context.hpp)
      s.ay[i] = sum(ay);
    }
    if constexpr (Scheme::continuity) s.drho[i] = sum(drho);
    if constexpr (kPredict) next.sum[i] = sum(wsum);
    // Times C_i, the -C div u term: the same sum for every species.
    const double dilatation = sum(cdil);
    double dci = double(sum(cdiff)) + ci_d * dilatation;
    if constexpr (Scheme::shifting) {
      double sxi, syi;
      ph.shifting(sum(gx), sum(gy), sxi, syi);
      s.sx[i] = static_cast<float>(sxi);
      s.sy[i] = static_cast<float>(syi);
      if constexpr (Ale) dci += sxi * double(sum(cgx)) + syi * double(sum(cgy));  // du_i . grad C_i
    }
    s.dc[i] = static_cast<float>(dci);
    if constexpr (Network) {
      const float sums[3] = {sum(cd1), sum(cd2), sum(cd3)};
      const double ci_more[3] = {more > 0 ? s.c_more[0][i] : 0.0, more > 1 ? s.c_more[1][i] : 0.0,
                                 more > 2 ? s.c_more[2][i] : 0.0};
      for (int e = 0; e < more; ++e)
        s.dc_more[e][i] = static_cast<float>(double(sums[e]) + ci_more[e] * dilatation);
    }
  }
}

// The force pass on the store's current state: the records filled, then the pair loop over the
// list's form. V: simd::F8, or simd::Portable8 to run the reference lanes (tests).
template <class Scheme, bool Ale, bool Diffuse = true, bool Network = false, class V = simd::F8>
void interaction_pass(ParticleStore& s, const PassContext& ctx, PairRecords& records) {
  using L = RecordLayout<Scheme::momentum, Network>;
  if constexpr (Scheme::summation_density)
    records.fill<L, 2>(s, ctx.phys.eos.rho0, ctx.next_density.dx, ctx.next_density.dy);
  else
    records.fill<L, Ale ? 1 : 0>(s, ctx.phys.eos.rho0, s.fluid_side.data(), nullptr);
  ctx.neighbours.with_indices([&](auto form) {
    interaction_pass_with<Scheme, Ale, Diffuse, Network, V>(s, ctx, records.data(), form);
  });
}

}  // namespace adrsph
