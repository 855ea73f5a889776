#include "schemes/density_passes.hpp"

namespace adrsph {

void summation_density(ParticleStore& s, const PassContext& ctx) {
  const std::size_t n = s.size();
  const double* x = s.x.data();
  const double* y = s.y.data();
  const std::uint32_t* nb = ctx.neighbours.data();
  const double self = ctx.kernel.value(0.0);
  const double mass = ctx.phys.mass;
  // Local copies: with references g++ reloaded them in the loop (2x slower, measured).
  const TaitEos eos = ctx.phys.eos;
  const QuinticKernel kernel = ctx.kernel;
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    if (s.kind[i] != static_cast<std::uint8_t>(Kind::fluid)) continue;
    const double xi = x[i], yi = y[i];
    // Single-precision kernel sums, as in the force pass: their rounding (~1e-8 of rho) is
    // far below the summation's own error on disordered particles (~1e-4..1e-3 of rho).
    float sum = 0.0f;
    const std::uint32_t kb = ctx.neighbours.begin(i), ke = ctx.neighbours.end(i);
#pragma omp simd reduction(+ : sum)
    for (std::uint32_t k = kb; k < ke; ++k) {
      const std::uint32_t j = nb[k];
      const auto dx = static_cast<float>(xi - x[j]), dy = static_cast<float>(yi - y[j]);
      sum += kernel.value<float>(std::sqrt(dx * dx + dy * dy));
    }
    const double rhoi = mass * (self + static_cast<double>(sum));
    s.rho[i] = rhoi;
    s.p[i] = static_cast<float>(eos.pressure(rhoi));
    s.vol[i] = static_cast<float>(mass / rhoi);
  }
}

void fluid_pressure(ParticleStore& s, const TaitEos& eos, double mass) {
  const std::size_t n = s.size();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    if (s.kind[i] != static_cast<std::uint8_t>(Kind::fluid)) continue;
    s.p[i] = static_cast<float>(eos.pressure(s.rho[i]));
    s.vol[i] = static_cast<float>(mass / s.rho[i]);
  }
}

}  // namespace adrsph
