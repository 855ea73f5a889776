#include "schemes/pass_context.hpp"
#include "species/species_rate.hpp"
#include "species/wall_images.hpp"

namespace adrsph {

namespace {
template <class Neighbours>
double exchange_rate_with(const ParticleStore& s, const PassContext& ctx, const Neighbours form,
                          const double* c, double diffusivity) {
  const std::size_t n = s.size();
  const double eta2 = ctx.phys.eta2;
  double total = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : total)
  for (std::size_t i = 0; i < n; ++i) {
    if (s.kind[i] != kFluidByte) continue;
    double rate = 0.0;
    std::uint32_t row_buffer[NeighbourList::kRowBuffer];
    const NeighbourList::Row row = ctx.neighbours.row_of(form, i, row_buffer);
    for (std::uint32_t k = 0; k < row.stored; ++k) {
      const std::uint32_t j = row.index[k];
      if (s.kind[j] != kInletByte && s.kind[j] != kOutletByte) continue;
      const double dx = s.x[i] - s.x[j], dy = s.y[i] - s.y[j], r2 = dx * dx + dy * dy;
      double lap_weight = ctx.kernel.laplacian_weight(r2, eta2);
      if (ctx.phys.wall_image_y > 0.0)  // the buffer neighbour's image (species/wall_images.hpp)
        lap_weight += ctx.kernel.laplacian_weight(
            wall_image_r2(dx, s.y[i], s.y[j], ctx.phys.wall_image_y), eta2);
      rate += species_diffusion_pair<double>(diffusivity, s.volume(i), s.volume(j), lap_weight,
                                             c[i] - c[j], s.diffusion_mask(j));
    }
    total += s.volume(i) * rate;
  }
  return total;
}

}  // namespace

double species_buffer_exchange_rate(const ParticleStore& s, const PassContext& ctx, const double* c,
                                    double diffusivity) {
  return ctx.neighbours.with_indices(
      [&](auto form) { return exchange_rate_with(s, ctx, form, c, diffusivity); });
}

}  // namespace adrsph
