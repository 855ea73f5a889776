#include "species/diffusion_subcycling.hpp"

#include <cmath>

#include "species/species_rate.hpp"

namespace adrsph {

namespace {
constexpr auto kFluid = static_cast<std::uint8_t>(Kind::fluid);
constexpr auto kInlet = static_cast<std::uint8_t>(Kind::inlet);
constexpr auto kOutlet = static_cast<std::uint8_t>(Kind::outlet);
}  // namespace

void DiffusionSubcycler::compute_weights(const ParticleStore& s, const PassContext& ctx) {
  const std::size_t n = s.size();
  weight_.resize(ctx.neighbours.total());
  const std::uint32_t* nb = ctx.neighbours.data();
  const double* x = s.x.data();
  const double* y = s.y.data();
  const float* vol = s.vol.data();
  const float* cm = s.c_mask.data();
  const double eta2 = ctx.phys.eta2, diffusivity = ctx.phys.diffusivity;
  const QuinticKernel kernel = ctx.kernel;  // local copy: see interaction_pass.hpp
  float* w = weight_.data();
#pragma omp parallel for schedule(static)
  for (std::size_t i = 0; i < n; ++i) {
    if (s.kind[i] != kFluid) continue;
    const double xi = x[i], yi = y[i], voli = vol[i];
    const std::uint32_t kb = ctx.neighbours.begin(i), ke = ctx.neighbours.end(i);
#pragma omp simd
    for (std::uint32_t k = kb; k < ke; ++k) {
      const std::uint32_t j = nb[k];
      const double dx = xi - x[j], dy = yi - y[j], r2 = dx * dx + dy * dy;
      const double r = std::sqrt(r2) + 1e-30;
      const double lap_weight = kernel.derivative(r) * r / (r2 + eta2);
      // species_diffusion_pair(D, V_i, V_j, lap_weight, c_ij, mask) = w_ij (c_i - c_j)
      w[k] = static_cast<float>(species_diffusion_pair<double>(diffusivity, voli, vol[j],
                                                               lap_weight, 1.0, cm[j]));
    }
  }
}

double DiffusionSubcycler::rates(const ParticleStore& s, const PassContext& ctx,
                                 const std::vector<double>& c, std::vector<double>& rate,
                                 bool track) const {
  const std::size_t n = s.size();
  const std::uint32_t* nb = ctx.neighbours.data();
  const float* w = weight_.data();
  const double* cc = c.data();
  double exchange = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : exchange)
  for (std::size_t i = 0; i < n; ++i) {
    if (s.kind[i] != kFluid) continue;
    const double ci = cc[i];
    double sum = 0.0;
    const std::uint32_t kb = ctx.neighbours.begin(i), ke = ctx.neighbours.end(i);
#pragma omp simd reduction(+ : sum)
    for (std::uint32_t k = kb; k < ke; ++k)
      sum += w[k] * (ci - cc[nb[k]]);
    rate[i] = sum;
    if (track) {  // flux from the buffers, for the species balance (tests, diagnostics)
      double from_buffers = 0.0;
      for (std::uint32_t k = ctx.neighbours.begin(i); k < ctx.neighbours.end(i); ++k) {
        const std::uint8_t kj = s.kind[nb[k]];
        if (kj == kInlet || kj == kOutlet) from_buffers += w[k] * (ci - cc[nb[k]]);
      }
      exchange += s.vol[i] * from_buffers;
    }
  }
  return exchange;
}

double DiffusionSubcycler::advance(ParticleStore& s, const PassContext& ctx, double dt,
                                   int substeps, bool track) {
  compute_weights(s, ctx);
  const std::size_t n = s.size();
  c_mid_.assign(s.c.begin(), s.c.end());
  rate_.assign(n + 1, 0.0);
  const double h = dt / substeps;
  double exchange = 0.0;
  for (int sub = 0; sub < substeps; ++sub) {
    // Explicit midpoint: rate at C, half step, rate at the half state, full step.
    rates(s, ctx, s.c, rate_, false);
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) c_mid_[i] = s.kind[i] == kFluid ? s.c[i] + 0.5 * h * rate_[i] : s.c[i];
    exchange += h * rates(s, ctx, c_mid_, rate_, track);
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i)
      if (s.kind[i] == kFluid) s.c[i] += h * rate_[i];
  }
  return exchange;
}

}  // namespace adrsph
