#include "schemes/density_passes.hpp"

namespace adrsph {

void summation_density(ParticleStore& s, const PassContext& ctx) {
  const std::size_t n = s.size();
  const double* x = s.x.data();
  const double* y = s.y.data();
  const std::uint32_t* nb = ctx.neighbours.data();
  const double self = ctx.kernel.value(0.0);
  const double mass = ctx.phys.mass;
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
    s.rho[i] = mass * sum;
  }
}

void fluid_pressure(ParticleStore& s, const TaitEos& eos) {
  const std::size_t n = s.size();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i)
    if (s.kind[i] == static_cast<std::uint8_t>(Kind::fluid)) s.p[i] = eos.pressure(s.rho[i]);
}

void particle_volumes(ParticleStore& s, double mass) {
  const std::size_t n = s.size();
#pragma omp parallel for simd schedule(static)
  for (std::size_t i = 0; i < n; ++i) s.vol[i] = mass / s.rho[i];
}

}  // namespace adrsph
