// Density and pressure of the fluid particles (and the outflow buffer's fixed state) before
// the boundary and force passes.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "schemes/pass_context.hpp"

namespace adrsph {

// Conventional scheme: rho_i = m sum_j W_ij (self included), eq. (3) with W for the printed
// grad W (docs/benchmark.md, section 2), then p_i as fluid_pressure()
// does, for the fluid particles; the outflow buffer gets its fixed state.
// `predicted`: the sums the previous force pass took at these very positions (pass_context.hpp,
// DensityPrediction), used where present (not NaN) instead of a neighbour loop: the same sums
// to float rounding (Flow.ConventionalPredictedDensityIsTheSummationDensity), at a fraction of
// the cost.
void summation_density(ParticleStore& s, const PassContext& ctx, const float* predicted = nullptr);

// The same, and `each(i)` for every particle i (walls and buffers too) in the same loop: the
// conventional step computes the displacement of its first stage there (SphSolver::
// evaluate_impl; the second stage's is written by the first stage's update): neither takes a
// pass over the store of its own.
template <class EachParticle>
void summation_density(ParticleStore& s, const PassContext& ctx, const float* predicted,
                       EachParticle&& each);

// p_i = Tait(rho_i) (+ p_b), eq. (2) of the fluid particles; the outflow buffer gets its
// fixed state (outflow_state). The boundary pass sets walls and inflow buffer. (V_i = m / rho_i
// is computed where it is read: ParticleStore::volume.)
void fluid_pressure(ParticleStore& s, const TaitEos& eos);

// rho_i and what follows from it: p_i = Tait(rho_i) (+ p_b), eq. (2).
// The one place a density passes on to them.
inline void set_density_state(ParticleStore& s, std::size_t i, double rho, const TaitEos& eos) {
  s.rho[i] = rho;
  s.p[i] = static_cast<float>(eos.pressure(rho));
}

// The outflow buffer's state: the rest density rho0, so p = p_b exactly, the reference the
// walls near the outlet sample (boundary_extrapolation.cpp). Both density passes set it in
// their loop over the store, before the boundary pass reads it.
inline void outflow_state(ParticleStore& s, std::size_t i, const TaitEos& eos) {
  set_density_state(s, i, eos.rho0, eos);
}

namespace detail {
// sum_j W_ij over i's list (self excluded). Single-precision kernel sums, as in the force
// pass: their rounding (~1e-8 of rho) is far below the summation's own error on disordered
// particles (~1e-4..1e-3 of rho).
template <class Neighbours>
inline float kernel_sum(std::size_t i, const double* x, const double* y, const Neighbours& form,
                        const NeighbourList& list, const QuinticKernel& kernel) {
  const double xi = x[i], yi = y[i];
  float sum = 0.0f;
  std::uint32_t row_buffer[NeighbourList::kRowBuffer];
  const NeighbourList::Row row = list.row_of(form, i, row_buffer);
#pragma omp simd reduction(+ : sum)
  for (std::uint32_t k = 0; k < row.whole; ++k) {
    const std::uint32_t j = row.index[k];
    const auto dx = static_cast<float>(xi - x[j]), dy = static_cast<float>(yi - y[j]);
    sum += kernel.value<float>(std::sqrt(dx * dx + dy * dy));
  }
  return sum;
}

template <class Neighbours, class EachParticle>
void summation_density_with(ParticleStore& s, const PassContext& ctx, const float* predicted,
                            const Neighbours form, EachParticle& each) {
  const std::size_t n = s.size();
  const double* x = s.x.data();
  const double* y = s.y.data();
  const double self = ctx.kernel.value(0.0);
  const double mass = s.mass;
  // Local copies: with references g++ reloaded them in the loop (2x slower, measured).
  const TaitEos eos = ctx.phys.eos;
  const QuinticKernel kernel = ctx.kernel;
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    each(i);
    const std::uint8_t k = s.kind[i];
    if (k == kOutletByte) outflow_state(s, i, eos);
    if (k != kFluidByte) continue;
    // A prediction is missing (NaN) for a particle that was in the inflow buffer then.
    const float sum = predicted && !std::isnan(predicted[i])
                          ? predicted[i]
                          : kernel_sum(i, x, y, form, ctx.neighbours, kernel);
    set_density_state(s, i, mass * (self + static_cast<double>(sum)), eos);  // eq. (3)
  }
}
}  // namespace detail

template <class EachParticle>
void summation_density(ParticleStore& s, const PassContext& ctx, const float* predicted,
                       EachParticle&& each) {
  ctx.neighbours.with_indices(
      [&](auto form) { detail::summation_density_with(s, ctx, predicted, form, each); });
}

}  // namespace adrsph
