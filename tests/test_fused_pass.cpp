// The fused force pass (single-precision pair arithmetic, one shared division) against the
// same equations summed in double precision, pair by pair, on a jittered lattice with
// perturbed velocities, densities and concentrations (docs/physics.md, "Precision").
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "boundaries/boundary_extrapolation.hpp"
#include "integrator/sph_solver.hpp"
#include "kernels/quintic_kernel.hpp"
#include "schemes/continuity.hpp"
#include "schemes/density_passes.hpp"
#include "schemes/interaction_pass.hpp"
#include "schemes/momentum.hpp"
#include "schemes/scheme_traits.hpp"
#include "species/diffusion_subcycling.hpp"
#include "species/species_rate.hpp"
#include "species/wall_images.hpp"
#include "sph_test_cases.hpp"

namespace adrsph {
namespace {

struct Rates {
  double ax = 0, ay = 0, drho = 0, dc = 0;
  double scale_a = 0, scale_rho = 0, scale_c = 0;  // sums of |term|: what rounding is relative to
};

// Eqs. (6)-(8), (12) for fluid particle i over every particle within the support, in double.
Rates double_rates(const ParticleStore& s, std::size_t i, const Case& c) {
  const QuinticKernel w(c.h());
  const double mass = c.fluid.rho0 * c.particles.dx * c.particles.dx;
  const double eta2 = 0.01 * c.h() * c.h(), four_nu = 4.0 * c.fluid.nu;
  const double dh = 2.0 * c.modern.delta * c.h() * c.c0(), diffusivity = c.species.D;
  Rates r;
  double cdiff = 0, cdil = 0, cdiff_abs = 0, cdil_abs = 0;
  for (std::size_t j = 0; j < s.size(); ++j) {
    if (j == i) continue;
    const double dx = s.x[i] - s.x[j], dy = s.y[i] - s.y[j], r2 = dx * dx + dy * dy;
    if (r2 >= w.support * w.support) continue;
    const double F = w.gradient_factor(std::sqrt(r2)), gx = F * dx, gy = F * dy;
    const double lap = w.laplacian_weight(r2, eta2);
    const double vj = s.volume(j), ux = s.vx[i] - s.vx[j], uy = s.vy[i] - s.vy[j];
    const double udg = ux * gx + uy * gy;
    const double sp = pressure_gradient_pair(1.0 / s.rho[i], double(s.p[i]), double(s.p[j]), vj);
    const double sv = viscous_pair(mass, four_nu, 1.0 / (s.rho[i] + s.rho[j]), lap);
    r.ax += sp * gx + sv * ux;
    r.ay += sp * gy + sv * uy;
    r.scale_a += std::fabs(sp) * std::hypot(gx, gy) + std::fabs(sv) * std::hypot(ux, uy);
    const double cont = continuity_pair(s.rho[i], vj, udg);
    const double ddiff = density_diffusion_pair(dh, vj, s.rho[i] - s.rho[j], lap);
    r.drho += cont + ddiff;
    r.scale_rho += std::fabs(cont) + std::fabs(ddiff);
    const double cd = species_diffusion_pair(diffusivity, double(s.volume(i)), vj, lap,
                                             s.c[i] - s.c[j], double(s.diffusion_mask(j)));
    cdiff += cd;
    cdiff_abs += std::fabs(cd);
    const double dil = species_dilatation_pair(vj, udg);
    cdil += dil;
    cdil_abs += std::fabs(dil);
  }
  r.dc = cdiff + s.c[i] * cdil;
  r.scale_c = cdiff_abs + std::fabs(s.c[i]) * cdil_abs;
  return r;
}

// Fluid particles moved off the lattice by up to 0.2 dx, with perturbed velocities, densities
// and concentrations (the solver's lists must be rebuilt afterwards).
void disorder(ParticleStore& s, const Case& c, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.kind[i] != kFluidByte) continue;
    s.x[i] += 0.2 * c.particles.dx * u(rng);
    s.y[i] += 0.2 * c.particles.dx * u(rng);
    s.vx[i] += 0.05 * c.u_max() * u(rng);
    s.vy[i] = 0.05 * c.u_max() * u(rng);
    s.rho[i] = c.fluid.rho0 * (1.0 + 2e-3 * u(rng));
    s.c[i] = c.species.c_in * (0.5 + 0.1 * u(rng));
  }
}

TEST(FusedPass, FloatPairSumsMatchDoubleOnAJitteredLattice) {
  Case c = testing::short_channel(Scheme::modern, Flow::wcsph, 5.0);
  SphSolver solver(c);
  ParticleStore& s = solver.particles();
  disorder(s, c, 7);
  solver.rebuild();  // lists for the jittered positions
  solver.evaluate();
  int checked = 0;
  double worst_a = 0, worst_rho = 0, worst_c = 0;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.kind[i] != kFluidByte) continue;
    const Rates r = double_rates(s, i, c);
    worst_a = std::max(worst_a, std::hypot(s.ax[i] - r.ax, s.ay[i] - r.ay) / r.scale_a);
    worst_rho = std::max(worst_rho, std::fabs(s.drho[i] - r.drho) / r.scale_rho);
    worst_c = std::max(worst_c, std::fabs(s.dc[i] - r.dc) / r.scale_c);
    ++checked;
  }
  std::printf(
      "float pass against double, %d fluid particles, error relative to the sum of "
      "|pair terms|: momentum %.1e, continuity %.1e, species %.1e\n",
      checked, worst_a, worst_rho, worst_c);
  ASSERT_GT(checked, 100);
  // Single precision: each pair term carries ~1e-7 relative rounding and the sums of ~35
  // terms add it up; 1e-5 of the sum of |terms| allows that and nothing else (a wrong factor
  // or sign in any term is an O(1) error on this scale).
  EXPECT_LT(worst_a, 1e-5);
  EXPECT_LT(worst_rho, 1e-5);
  EXPECT_LT(worst_c, 1e-5);
}

// The passes read a row through NeighbourList::with_indices: 16-bit offsets expanded and padded
// per row, or 32-bit indices stored padded. Both forms list the same entries in the same
// order, so every pass must give the same values bit for bit, the sub-cycler to rounding (a
// row expanded past its end, or padding missing from one form, would not).
TEST(FusedPass, BothFormsOfTheListGiveTheSameValues) {
  Case c = testing::short_channel(Scheme::modern, Flow::wcsph, 5.0);
  SphSolver solver(c);
  ParticleStore& s = solver.particles();
  disorder(s, c, 11);
  solver.rebuild();  // sorted by solver.grid() for the jittered positions
  solver.evaluate();
  const std::size_t n = s.size();
  const auto x = std::span<const double>(s.x).first(n), y = std::span<const double>(s.y).first(n);
  NeighbourList narrow, wide;
  narrow.build(solver.grid(), x, y, solver.cutoff(), static_cast<std::uint32_t>(n));
  wide.build(solver.grid(), x, y, solver.cutoff(), static_cast<std::uint32_t>(n),
             NeighbourList::Width::wide);
  ASSERT_FALSE(narrow.wide());
  ASSERT_TRUE(wide.wide());
  PhysicsConstants phys = solver.physics();
  phys.wall_image_y = c.geometry.half_width;  // the wall-image pass runs too
  const double dt = solver.dt_limits().chosen;
  phys.set_step(c, dt);  // shifting as a step sets it
  struct Values {
    std::vector<float> ax, ay, drho, dc, sx, sy, p_wall;
    std::vector<double> rho_summed, c_subcycled;
    double exchange = 0.0, exchange_subcycled = 0.0;
  };
  auto run_passes = [&](const NeighbourList& list) {
    const PassContext ctx{solver.kernel(), list, phys};
    ParticleStore t = s;  // each form from the same state
    Values v;
    extrapolate_to_boundaries(t, ctx);
    PairRecords records;
    interaction_pass<ModernScheme, false>(t, ctx, records);
    add_wall_image_diffusion(t, ctx);
    v.exchange = species_buffer_exchange_rate(t, ctx, t.c.data(), c.species.D);
    for (std::size_t i = 0; i < n; ++i)
      if (t.kind[i] == kWallByte) v.p_wall.push_back(t.p[i]);
    v.ax.assign(t.ax.begin(), t.ax.begin() + n);
    v.ay.assign(t.ay.begin(), t.ay.begin() + n);
    v.drho.assign(t.drho.begin(), t.drho.begin() + n);
    v.dc.assign(t.dc.begin(), t.dc.begin() + n);
    v.sx.assign(t.sx.begin(), t.sx.begin() + n);
    v.sy.assign(t.sy.begin(), t.sy.begin() + n);
    summation_density(t, ctx, nullptr, [](std::size_t) {});
    v.rho_summed.assign(t.rho.begin(), t.rho.begin() + n);
    DiffusionSubcycler subcycler;  // weights stored per entry of the list
    v.exchange_subcycled =
        subcycler.advance(t, ctx, 4.0 * dt, DiffusionSubcycler::plan(4.0), true)[0];
    v.c_subcycled.assign(t.c.begin(), t.c.begin() + n);
    return v;
  };
  const Values a = run_passes(narrow), b = run_passes(wide);
  EXPECT_EQ(a.ax, b.ax);
  EXPECT_EQ(a.ay, b.ay);
  EXPECT_EQ(a.drho, b.drho);
  EXPECT_EQ(a.dc, b.dc);
  EXPECT_EQ(a.sx, b.sx);
  EXPECT_EQ(a.sy, b.sy);
  EXPECT_EQ(a.p_wall, b.p_wall);
  EXPECT_EQ(a.rho_summed, b.rho_summed);
  EXPECT_EQ(a.exchange, b.exchange);
  // The sub-cycler keeps a weight per stored entry and sums over the stored row: the 32-bit
  // form's padding adds exact zeros, but the compiler may group a row's terms differently
  // for rows of another length (clang's vectorisation does), so equal to rounding only.
  ASSERT_EQ(a.c_subcycled.size(), b.c_subcycled.size());
  double c_diff = 0.0;
  for (std::size_t i = 0; i < n; ++i)
    c_diff = std::max(c_diff, std::fabs(a.c_subcycled[i] - b.c_subcycled[i]));
  std::printf("sub-cycled C, 16-bit against 32-bit list: largest difference %.1e mol/m^3\n",
              c_diff);
  EXPECT_LT(c_diff, 1e-12 * c.species.c_in);
  EXPECT_NEAR(a.exchange_subcycled, b.exchange_subcycled, 1e-12 * std::fabs(a.exchange_subcycled));
  EXPECT_NE(a.exchange_subcycled, 0.0);
  EXPECT_NE(a.exchange, 0.0);  // the buffers are within reach of the fluid
  // Not all zero: the passes ran on a state with flow, shifting and gradients of C.
  EXPECT_GT(*std::max_element(a.dc.begin(), a.dc.end()), 0.0f);
  EXPECT_GT(*std::max_element(a.sx.begin(), a.sx.end()), 0.0f);
}

}  // namespace
}  // namespace adrsph
