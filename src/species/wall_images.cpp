#include "species/wall_images.hpp"

#include "species/species_rate.hpp"

namespace adrsph {

namespace {
template <class Neighbours>
void add_with(ParticleStore& s, const PassContext& ctx, const Neighbours form) {
  const std::size_t n = s.size();
  const double wall_y = ctx.phys.wall_image_y, eta2 = ctx.phys.eta2;
  const QuinticKernel kernel = ctx.kernel;  // local copy: see interaction_pass.hpp
  const double reach = kernel.support, reach2 = reach * reach;
  const int more = s.needs().more_species;
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    // Only particles within the support of a wall have images within theirs.
    if (s.kind[i] != kFluidByte || wall_y - std::fabs(s.y[i]) >= reach) continue;
    const double xi = s.x[i], yi = s.y[i], voli = s.volume(i);
    double sum = 0.0, sum_more[ParticleStore::kMaxMore] = {};
    std::uint32_t row_buffer[NeighbourList::kRowBuffer];
    const NeighbourList::Row row = ctx.neighbours.row_of(form, i, row_buffer);
    for (std::uint32_t k = 0; k < row.stored; ++k) {
      const std::uint32_t j = row.index[k];
      const float dmask = ParticleStore::diffusion_mask_of(s.kind[j]);
      if (dmask == 0.0f) continue;  // walls and the outflow buffer carry no diffusion
      const double r2 = wall_image_r2(xi - s.x[j], yi, s.y[j], wall_y);
      if (r2 >= reach2) continue;
      const double weight = species_diffusion_pair<double>(
          1.0, voli, s.volume(j), kernel.laplacian_weight(r2, eta2), 1.0, dmask);
      sum += weight * (s.c[i] - s.c[j]);
      for (int e = 0; e < more; ++e) sum_more[e] += weight * (s.c_more[e][i] - s.c_more[e][j]);
    }
    s.dc[i] = static_cast<float>(double(s.dc[i]) + ctx.phys.diffusivity * sum);
    for (int e = 0; e < more; ++e)
      s.dc_more[e][i] =
          static_cast<float>(double(s.dc_more[e][i]) + ctx.phys.more_diffusivity[e] * sum_more[e]);
  }
}
}  // namespace

void add_wall_image_diffusion(ParticleStore& s, const PassContext& ctx) {
  ctx.neighbours.with_indices([&](auto form) { add_with(s, ctx, form); });
}

}  // namespace adrsph
