#include "boundaries/boundary_extrapolation.hpp"

namespace adrsph {

namespace {
template <class Neighbours>
void extrapolate_with(ParticleStore& s, const PassContext& ctx, const Neighbours form) {
  const std::size_t n = s.size();
  const double* x = s.x.data();
  const double* y = s.y.data();
  const float* p = s.p.data();
  const double* vx = s.vx.data();
  const double* vy = s.vy.data();
  const std::uint8_t* kind = s.kind.data();
  const float* side = s.fluid_side.data();
  const TaitEos eos = ctx.phys.eos;
  const QuinticKernel kernel = ctx.kernel;  // local copies: see interaction_pass.hpp
  // The outflow buffer's state (p_b, rho0) was set by the density pass before this one
  // (density_passes.hpp, outflow_state): the walls near the outlet sample it.
  // Walls and inlet read only fluid and outlet particles (fluid_side = 1) and write only their
  // own p, rho, V and wall velocity. The reads of a neighbour's p and velocity are behind the
  // mask, not multiplied by it, so no thread ever reads a boundary value that another thread
  // is writing (a data race even when the product is zero).
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    const std::uint8_t ki = kind[i];
    if (ki != kWallByte && ki != kInletByte) continue;
    const double xi = x[i], yi = y[i];
    // Single precision, like the other neighbour passes (shepard averages of float p).
    float sw = 0.0f, sp = 0.0f, su = 0.0f, sv = 0.0f;
    std::uint32_t row_buffer[NeighbourList::kRowBuffer];
    const NeighbourList::Row row = ctx.neighbours.row_of(form, i, row_buffer);
#pragma omp simd reduction(+ : sw, sp, su, sv)
    for (std::uint32_t k = 0; k < row.whole; ++k) {
      const std::uint32_t j = row.index[k];
      const auto dx = static_cast<float>(xi - x[j]), dy = static_cast<float>(yi - y[j]);
      // Fluid and outlet particles are the "fluid side" a boundary particle samples (a float
      // mask, not kind[j]: a byte gather keeps g++ from vectorising the loop).
      const bool sampled = side[j] > 0.0f;
      const float w = sampled ? side[j] * kernel.value<float>(std::sqrt(dx * dx + dy * dy)) : 0.0f;
      sw += w;
      sp += w * (sampled ? p[j] : 0.0f);
      su += w * (sampled ? static_cast<float>(vx[j]) : 0.0f);
      sv += w * (sampled ? static_cast<float>(vy[j]) : 0.0f);
    }
    const double pw = sw > 0.0f ? double(sp) / sw : eos.p_background;
    const double rhow = eos.density(pw);
    s.p[i] = static_cast<float>(pw);
    s.rho[i] = rhow;
    if (ki == kWallByte) {
      s.vx[i] = sw > 0.0f ? -double(su) / sw : 0.0;
      s.vy[i] = sw > 0.0f ? -double(sv) / sw : 0.0;
    }
  }
}

}  // namespace

void extrapolate_to_boundaries(ParticleStore& s, const PassContext& ctx) {
  ctx.neighbours.with_indices([&](auto form) { extrapolate_with(s, ctx, form); });
}

}  // namespace adrsph
