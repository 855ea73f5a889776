#include "schemes/density_passes.hpp"

#include <cmath>

namespace adrsph {

void summation_density(ParticleStore& s, const PassContext& ctx, const float* predicted) {
  summation_density(s, ctx, predicted, [](std::size_t) {});
}

void fluid_pressure(ParticleStore& s, const TaitEos& eos) {
  const std::size_t n = s.size();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t k = s.kind[i];
    if (k == kOutletByte) outflow_state(s, i, eos);
    if (k != kFluidByte) continue;
    set_density_state(s, i, s.rho[i], eos);
  }
}

}  // namespace adrsph
