#include "schemes/density_passes.hpp"

namespace adrsph {

void summation_density(ParticleStore& s, const PassContext& ctx) {
  const std::size_t n = s.size();
  const double* x = s.x.data();
  const double* y = s.y.data();
  const std::uint32_t* nb = ctx.neighbours.data();
  const double self = ctx.kernel.value(0.0);
  const double mass = ctx.phys.mass;
  const TaitEos& eos = ctx.phys.eos;
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    if (s.kind[i] != static_cast<std::uint8_t>(Kind::fluid)) continue;
    const double xi = x[i], yi = y[i];
    double sum = self;
#pragma omp simd reduction(+ : sum)
    for (std::uint32_t k = ctx.neighbours.begin(i); k < ctx.neighbours.end(i); ++k) {
      const std::uint32_t j = nb[k];
      const double dx = xi - x[j], dy = yi - y[j];
      sum += ctx.kernel.value(std::sqrt(dx * dx + dy * dy));
    }
    const double rhoi = mass * sum;
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
