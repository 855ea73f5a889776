#include "schemes/density_passes.hpp"

#include <cmath>

namespace adrsph {

namespace {
// sum_j W_ij over i's list (self excluded). Single-precision kernel sums, as in the force
// pass: their rounding (~1e-8 of rho) is far below the summation's own error on disordered
// particles (~1e-4..1e-3 of rho).
template <class Neighbours>
inline float kernel_sum(std::size_t i, const double* x, const double* y, const Neighbours& form,
                        const NeighbourList& list, const QuinticKernel& kernel) {
  const double xi = x[i], yi = y[i];
  float sum = 0.0f;
  const std::uint32_t kb = list.begin(i), ke = list.end(i);
  std::uint32_t row_buffer[NeighbourList::kMaxRow];
  const std::uint32_t* nb = form.row(i, kb, ke, row_buffer);
  const std::uint32_t len = ke - kb;
#pragma omp simd reduction(+ : sum)
  for (std::uint32_t k = 0; k < len; ++k) {
    const std::uint32_t j = nb[k];
    const auto dx = static_cast<float>(xi - x[j]), dy = static_cast<float>(yi - y[j]);
    sum += kernel.value<float>(std::sqrt(dx * dx + dy * dy));
  }
  return sum;
}

// rho_i = m (W(0) + sum), then p_i (eq. 2) and V_i.
inline void set_density(ParticleStore& s, std::size_t i, double self, float sum, double mass,
                        const TaitEos& eos) {
  const double rhoi = mass * (self + static_cast<double>(sum));
  s.rho[i] = rhoi;
  s.p[i] = static_cast<float>(eos.pressure(rhoi));
  s.vol[i] = static_cast<float>(mass / rhoi);
}

template <class Neighbours>
void summation_density_with(ParticleStore& s, const PassContext& ctx, const float* predicted,
                            const Neighbours form) {
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
    if (s.kind[i] != kFluidByte) continue;
    // A prediction is missing (NaN) for a particle that was in the inflow buffer then.
    const float sum = predicted && !std::isnan(predicted[i])
                          ? predicted[i]
                          : kernel_sum(i, x, y, form, ctx.neighbours, kernel);
    set_density(s, i, self, sum, mass, eos);
  }
}
}  // namespace

void summation_density(ParticleStore& s, const PassContext& ctx, const float* predicted) {
  ctx.neighbours.with_indices([&](auto form) { summation_density_with(s, ctx, predicted, form); });
}

void fluid_pressure(ParticleStore& s, const TaitEos& eos, double mass) {
  const std::size_t n = s.size();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    if (s.kind[i] != kFluidByte) continue;
    s.p[i] = static_cast<float>(eos.pressure(s.rho[i]));
    s.vol[i] = static_cast<float>(mass / s.rho[i]);
  }
}

}  // namespace adrsph
