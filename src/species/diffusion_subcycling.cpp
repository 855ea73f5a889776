#include "species/diffusion_subcycling.hpp"

#include <cmath>

#include "species/species_rate.hpp"
#include "species/wall_images.hpp"

namespace adrsph {

namespace {
// Images = particles.wall_images (species/wall_images.hpp), a template parameter so that the
// pair loop carries no branch on it.
template <bool Images, class Neighbours>
void compute_weights_with(const ParticleStore& s, const PassContext& ctx, const Neighbours form,
                          float* w) {
  const std::size_t n = s.size();
  const double* x = s.x.data();
  const double* y = s.y.data();
  const double* rho = s.rho.data();
  const std::uint8_t* kind = s.kind.data();
  const double mass = s.mass;
  const double eta2 = ctx.phys.eta2, diffusivity = ctx.phys.max_diffusivity;
  const double wall_y = ctx.phys.wall_image_y;
  const QuinticKernel kernel = ctx.kernel;  // local copy: see interaction_pass.hpp
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    if (s.kind[i] != kFluidByte) continue;
    const double xi = x[i], yi = y[i], voli = s.volume(i);
    std::uint32_t row_buffer[NeighbourList::kRowBuffer];
    const NeighbourList::Row row = ctx.neighbours.row_of(form, i, row_buffer);
    float* wi = w + row.first;  // a weight per stored entry (neighbour_list.hpp: which are stored)
#pragma omp simd
    for (std::uint32_t k = 0; k < row.stored; ++k) {
      const std::uint32_t j = row.index[k];
      const double dx = xi - x[j], dy = yi - y[j], r2 = dx * dx + dy * dy;
      double lap_weight = kernel.laplacian_weight(r2, eta2);
      // The image of j across the wall (species/wall_images.hpp): the same C_j, so its weight
      // adds to the pair's; laplacian_weight is 0 beyond the support.
      if constexpr (Images)
        lap_weight += kernel.laplacian_weight(wall_image_r2(dx, yi, y[j], wall_y), eta2);
      // species_diffusion_pair(D, V_i, V_j, lap_weight, c_ij, mask) = w_ij (c_i - c_j)
      const double volj = ParticleStore::volume_of(mass, rho[j]);
      wi[k] = static_cast<float>(species_diffusion_pair<double>(
          diffusivity, voli, volj, lap_weight, 1.0, ParticleStore::diffusion_mask_of(kind[j])));
    }
  }
}

template <class Neighbours>
double rates_with(const ParticleStore& s, const PassContext& ctx, const Neighbours form,
                  const float* w, const double* cc, double factor, std::vector<double>& rate,
                  bool track) {
  const std::size_t n = s.size();
  double exchange = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : exchange)
  for (std::size_t i = 0; i < n; ++i) {
    if (s.kind[i] != kFluidByte) continue;
    const double ci = cc[i];
    double sum = 0.0;
    std::uint32_t row_buffer[NeighbourList::kRowBuffer];
    const NeighbourList::Row row = ctx.neighbours.row_of(form, i, row_buffer);
    const float* wi = w + row.first;
#pragma omp simd reduction(+ : sum)
    for (std::uint32_t k = 0; k < row.stored; ++k) sum += wi[k] * (ci - cc[row.index[k]]);
    rate[i] = factor * sum;
    if (track) {  // flux from the buffers, for the species balance (tests, diagnostics)
      double from_buffers = 0.0;
      for (std::uint32_t k = 0; k < row.stored; ++k) {
        const std::uint32_t j = row.index[k];
        const std::uint8_t kj = s.kind[j];
        if (kj == kInletByte || kj == kOutletByte) from_buffers += wi[k] * (ci - cc[j]);
      }
      exchange += s.volume(i) * factor * from_buffers;
    }
  }
  return exchange;
}
}  // namespace

void DiffusionSubcycler::compute_weights(const ParticleStore& s, const PassContext& ctx) {
  weight_.resize(ctx.neighbours.total());
  ctx.neighbours.with_indices([&](auto form) {
    if (ctx.phys.wall_image_y > 0.0)
      compute_weights_with<true>(s, ctx, form, weight_.data());
    else
      compute_weights_with<false>(s, ctx, form, weight_.data());
  });
}

double DiffusionSubcycler::rates(const ParticleStore& s, const PassContext& ctx,
                                 const std::vector<double>& c, double factor,
                                 std::vector<double>& rate, bool track) const {
  return ctx.neighbours.with_indices([&](auto form) {
    return rates_with(s, ctx, form, weight_.data(), c.data(), factor, rate, track);
  });
}

DiffusionSubcycler::Plan DiffusionSubcycler::plan(double ratio) {
  // RKL2 is stable for dt <= dt_explicit (s^2 + s - 2) / 4. Stability alone would allow one
  // super-step of many stages over any dt, but its time error grows with the super-step:
  // each covers at most kMaxLimits explicit limits (4 stages), so accuracy stays close to
  // that of explicit steps while the products per step halve (Pe = 10: ratio 3.6, 1 x 4).
  constexpr double kMaxLimits = 4.5;
  Plan p;
  p.supersteps = std::max(1, static_cast<int>(std::ceil(ratio / kMaxLimits * (1.0 - 1e-12))));
  const double per = ratio / p.supersteps;
  p.stages = 2;
  while ((p.stages * p.stages + p.stages - 2) / 4.0 < per * (1.0 - 1e-12)) ++p.stages;
  return p;
}

std::array<double, Case::kMaxSpecies> DiffusionSubcycler::advance(ParticleStore& s,
                                                                  const PassContext& ctx, double dt,
                                                                  Plan plan, bool track) {
  compute_weights(s, ctx);  // the configuration is frozen over the step
  std::array<double, Case::kMaxSpecies> exchange{};
  const double h = dt / plan.supersteps;
  const double d_max = ctx.phys.max_diffusivity;
  auto factor = [d_max](double d) { return d_max > 0.0 ? d / d_max : 0.0; };
  const double f0 = factor(ctx.phys.diffusivity);
  for (int k = 0; k < plan.supersteps; ++k)
    exchange[0] += superstep(s, s.c, f0, ctx, h, plan.stages, track);
  for (int e = 0; e < s.needs().more_species; ++e)
    for (int k = 0; k < plan.supersteps; ++k)
      exchange[static_cast<std::size_t>(e) + 1] += superstep(
          s, s.c_more[e], factor(ctx.phys.more_diffusivity[e]), ctx, h, plan.stages, track);
  return exchange;
}

double DiffusionSubcycler::superstep(ParticleStore& s, std::vector<double>& c, double factor,
                                     const PassContext& ctx, double dt, int stages, bool track) {
  // One RKL2 super-step (Meyer, Balsara & Aslam, J. Comput. Phys. 257, 2014, eqs. 16-18):
  //   Y1 = Y0 + mu~1 dt L(Y0)
  //   Yj = mu_j Y(j-1) + nu_j Y(j-2) + (1 - mu_j - nu_j) Y0 + mu~j dt L(Y(j-1)) + g~j dt L(Y0)
  // Second order, s sparse products per step, stable for real negative spectra up to
  // (s^2 + s - 2)/4 explicit limits: the diffusion operator here is symmetric (w_ij = w_ji).
  // The midpoint sub-steps it replaced cost 2 products per explicit limit.
  const std::size_t n = s.size() + 1;
  const int st = std::max(stages, 2);
  const double w1 = 4.0 / (static_cast<double>(st) * st + st - 2.0);
  auto b = [](int j) { return j < 2 ? 1.0 / 3.0 : (j * j + j - 2.0) / (2.0 * j * (j + 1.0)); };
  y0_.assign(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(n));
  l0_.assign(n, 0.0);  // rates are written for fluid particles only: the rest stays 0
  rate_.assign(n, 0.0);
  // Y_j - Y0 = dt sum_k beta_j[k] L(Y_k): the buffer exchange, linear in the rates, follows.
  std::vector<double> e(st, 0.0), beta_m2(st, 0.0), beta_m1(st, 0.0), beta(st, 0.0);
  e[0] = rates(s, ctx, y0_, factor, l0_, track);
  ym2_ = y0_;
  ym1_.resize(n);
  const double mu1 = b(1) * w1;
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) ym1_[i] = y0_[i] + mu1 * dt * l0_[i];
  beta_m1[0] = mu1;
  yj_.resize(n);
  for (int j = 2; j <= st; ++j) {
    const double mu = (2.0 * j - 1.0) / j * b(j) / b(j - 1);
    const double nu = -(j - 1.0) / j * b(j) / b(j - 2);
    const double mut = mu * w1;
    const double gt = -(1.0 - b(j - 1)) * mut;
    e[j - 1] = rates(s, ctx, ym1_, factor, rate_, track);
    const double* y0 = y0_.data();
    const double* l0 = l0_.data();
    const double* r = rate_.data();
    const double* a1 = ym1_.data();
    const double* a2 = ym2_.data();
    double* out = yj_.data();
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
      out[i] =
          mu * a1[i] + nu * a2[i] + (1.0 - mu - nu) * y0[i] + mut * dt * r[i] + gt * dt * l0[i];
    for (int k = 0; k < st; ++k)
      beta[k] = mu * beta_m1[k] + nu * beta_m2[k] + (k == j - 1 ? mut : 0.0) + (k == 0 ? gt : 0.0);
    std::swap(ym2_, ym1_);
    std::swap(ym1_, yj_);  // Y(j-1) <- Yj, Y(j-2) <- old Y(j-1)
    std::swap(beta_m2, beta_m1);
    std::swap(beta_m1, beta);
  }
  double exchange = 0.0;
  for (int k = 0; k < st; ++k) exchange += dt * beta_m1[k] * e[k];
  // Buffers and walls: rates 0, coefficients summing to 1, so their C is unchanged; copy the
  // fluid values only all the same (rounding of the coefficient sum).
  const std::size_t real = n - 1;
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < real; ++i)
    if (s.kind[i] == kFluidByte) c[i] = ym1_[i];
  return exchange;
}

}  // namespace adrsph
