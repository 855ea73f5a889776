// The record form of the force pass (schemes/pair_records.hpp, schemes/simd8.hpp): the
// transposition of eight records, the hi/lo split of the doubles, and the pass run with the AVX
// lanes against the portable ones for every scheme (the portable lanes are plain loops over
// eight floats: what the AVX code must reproduce to rounding).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>

#include "boundaries/boundary_extrapolation.hpp"
#include "integrator/sph_solver.hpp"
#include "schemes/density_passes.hpp"
#include "schemes/interaction_pass.hpp"
#include "schemes/pair_records.hpp"
#include "schemes/scheme_traits.hpp"
#include "schemes/simd8.hpp"
#include "sph_test_cases.hpp"

namespace adrsph {
namespace {

template <class V>
std::array<float, 8> lanes(const V& v) {
  std::array<float, 8> out{};
  v.store(out.data());
  return out;
}

template <class V>
class Lanes : public ::testing::Test {};
#if defined(__AVX__)
using LaneTypes = ::testing::Types<simd::Portable8, simd::Avx8>;
#else
using LaneTypes = ::testing::Types<simd::Portable8>;
#endif
TYPED_TEST_SUITE(Lanes, LaneTypes);

// Lane k of field f must be field f of record k, for both blocks of a 16-field record and for
// records anywhere in the array (a swapped shuffle constant or half would mix them).
TYPED_TEST(Lanes, TransposeGivesEachFieldOfEachRecord) {
  constexpr int kFields = 16;
  std::vector<float> data(20 * kFields);
  for (std::size_t e = 0; e < data.size(); ++e) data[e] = static_cast<float>(e);
  const int picked[8] = {19, 3, 7, 0, 12, 12, 5, 18};  // repeats happen: the padding particle
  const float* records[8];
  for (int k = 0; k < 8; ++k) records[k] = data.data() + picked[k] * kFields;
  TypeParam out[kFields];
  for (int block = 0; block < kFields; block += 8)
    TypeParam::transpose(records, block, out + block);
  for (int f = 0; f < kFields; ++f) {
    const auto got = lanes(out[f]);
    for (int k = 0; k < 8; ++k) EXPECT_EQ(got[k], float(picked[k] * kFields + f)) << f << " " << k;
  }
}

TYPED_TEST(Lanes, ArithmeticAndSumActLaneByLane) {
  float a[8], b[8];
  for (int k = 0; k < 8; ++k) a[k] = 1.5f + k, b[k] = -0.25f * (k + 1);
  const float* ra[8] = {a, a, a, a, a, a, a, a};  // record k = a: field f is a[f] in every lane
  TypeParam va[8], vb[8];
  TypeParam::transpose(ra, 0, va);
  const float* rb[8] = {b, b, b, b, b, b, b, b};
  TypeParam::transpose(rb, 0, vb);
  for (int f = 0; f < 8; ++f) {
    const auto r = lanes(sqrt(va[f] * va[f]) / TypeParam(2) + fabs(vb[f]) - max(va[f], vb[f]));
    for (int k = 0; k < 8; ++k) EXPECT_EQ(r[k], a[f] / 2 + std::fabs(b[f]) - a[f]);
    EXPECT_EQ(sum(va[f]), 8 * a[f]);
    EXPECT_EQ(lanes(-vb[f])[0], -b[f]);
  }
}

// v_i - v_j from the hi/lo parts is the double difference rounded once (or within one more
// rounding of it): positions ~1e2 mm apart by ~1e-1 mm, and of both signs near 0.
TEST(PairRecords, HiLoDifferenceIsTheDoubleDifferenceRounded) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> where(-1.0, 100.0), apart(-0.4, 0.4);
  double worst = 0.0;
  for (int t = 0; t < 100000; ++t) {
    const double a = where(rng), b = a + apart(rng);
    float ah, al, bh, bl;
    split_hi_lo(a, ah, al);
    split_hi_lo(b, bh, bl);
    const float d = (ah - bh) + (al - bl);
    const double exact = a - b;
    worst = std::max(worst, std::fabs(d - exact) / std::fabs(exact));
  }
  std::printf("hi/lo difference against the double difference: worst relative error %.2e\n", worst);
  // float(a - b) alone is within 2^-24 = 6.0e-8; the lo parts add at most as much again.
  EXPECT_LT(worst, 1.2e-7);
  // What a single float per value would give instead (the reason for the lo part).
  const double a = 87.123456789, b = a - 0.0123456789;
  const float plain = static_cast<float>(a) - static_cast<float>(b);
  EXPECT_GT(std::fabs(plain - (a - b)) / (a - b), 1e-6);
}

struct Rates {
  std::vector<float> ax, ay, drho, dc, sx, sy, next_sum;
};

// One variant of the pass with lanes V on a copy of the solver's state.
template <class S, bool Ale, class V>
Rates rates_with(const SphSolver& solver, const NeighbourList& list, const ParticleStore& state,
                 const Case& c) {
  ParticleStore t = state;
  PhysicsConstants phys = solver.physics();
  phys.set_step(c, solver.dt_limits().chosen);
  PassContext ctx{solver.kernel(), list, phys};
  const std::size_t n = t.size();
  std::vector<float> next_sum(n + 1, 0.0f), ddx(n + 1, 0.0f), ddy(n + 1, 0.0f);
  for (std::size_t i = 0; i < n; ++i)  // a displacement like a stage's: ~0.05 dx
    if (t.kind[i] == kFluidByte) {
      ddx[i] = static_cast<float>(0.05 * c.particles.dx * std::sin(1.7 * i));
      ddy[i] = static_cast<float>(0.05 * c.particles.dx * std::cos(2.3 * i));
    }
  if constexpr (S::summation_density) ctx.next_density = {next_sum.data(), ddx.data(), ddy.data()};
  PairRecords records;
  interaction_pass<S, Ale, true, false, V>(t, ctx, records);
  auto take = [n](const std::vector<float>& v) {
    return std::vector<float>(v.begin(), v.begin() + std::min(n, v.size()));
  };
  Rates r;
  if constexpr (S::momentum) r.ax = take(t.ax), r.ay = take(t.ay);
  if constexpr (S::continuity) r.drho = take(t.drho);
  if constexpr (S::shifting) r.sx = take(t.sx), r.sy = take(t.sy);
  if constexpr (S::summation_density) r.next_sum = take(next_sum);
  r.dc = take(t.dc);
  return r;
}

// Largest |a - b| over the fluid particles, relative to the largest |a|.
double field_difference(const std::vector<float>& a, const std::vector<float>& b,
                        const ParticleStore& s) {
  double diff = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (s.kind[i] != kFluidByte) continue;
    diff = std::max(diff, double(std::fabs(a[i] - b[i])));
    scale = std::max(scale, double(std::fabs(a[i])));
  }
  return scale > 0.0 ? diff / scale : (diff > 0.0 ? 1.0 : 0.0);
}

template <class S, bool Ale>
void expect_lanes_agree(Scheme scheme, const char* name) {
  Case c = testing::short_channel(scheme, S::momentum ? Flow::wcsph : Flow::prescribed, 5.0);
  c.species.ale = Ale;
  SphSolver solver(c);
  ParticleStore& s = solver.particles();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s.kind[i] != kFluidByte) continue;
    s.x[i] += 0.2 * c.particles.dx * u(rng);
    s.y[i] += 0.2 * c.particles.dx * u(rng);
    s.vy[i] = 0.05 * c.u_max() * u(rng);
    s.rho[i] = c.fluid.rho0 * (1.0 + 2e-3 * u(rng));
    s.c[i] = c.species.c_in * (0.5 + 0.1 * u(rng));
  }
  solver.rebuild();
  solver.evaluate();  // p, V, rho - rho0, the walls' extrapolated state
  const std::size_t n = s.size();
  NeighbourList list;
  list.build(solver.grid(), std::span<const double>(s.x).first(n),
             std::span<const double>(s.y).first(n), solver.cutoff(), static_cast<std::uint32_t>(n));
  const Rates a = rates_with<S, Ale, simd::Portable8>(solver, list, s, c);
  const Rates b = rates_with<S, Ale, simd::F8>(solver, list, s, c);
  const std::pair<const std::vector<float>*, const std::vector<float>*> fields[] = {
      {&a.ax, &b.ax}, {&a.ay, &b.ay}, {&a.drho, &b.drho},        {&a.dc, &b.dc},
      {&a.sx, &b.sx}, {&a.sy, &b.sy}, {&a.next_sum, &b.next_sum}};
  double worst = 0.0;
  int compared = 0;
  for (const auto& [pa, pb] : fields) {
    ASSERT_EQ(pa->size(), pb->size());
    if (pa->empty()) continue;
    worst = std::max(worst, field_difference(*pa, *pb, s));
    ++compared;
  }
  std::printf("%s%s: %d rates, F8 lanes against portable lanes, worst %.1e of the largest\n", name,
              Ale ? " (ALE)" : "", compared, worst);
  EXPECT_GE(compared, S::momentum ? 3 : 1);
  // Contractions into fused multiply-adds may differ between the two: ~1e-7 per term, on sums
  // that cancel to ~1e-2 of their terms.
  EXPECT_LT(worst, 1e-4);
  // Not all zero: the variant's rates ran on a state with flow and gradients of C.
  EXPECT_GT(field_difference(a.dc, std::vector<float>(a.dc.size(), 0.0f), s), 0.0);
}

// The fill takes V = m / rho and the diffusion mask from the state, which does not store them:
// each record holds V of its particle's density and the mask of its kind (1 for fluid and the
// inflow buffer, 0 for walls and the outflow buffer), the padding particle's included.
TEST(PairRecords, FillTakesVolumeFromDensityAndMaskFromKind) {
  const Case c = testing::short_channel(Scheme::modern, Flow::wcsph, 5.0);
  SphSolver solver(c);
  const double dt = solver.dt_limits().chosen;
  for (int k = 0; k < 20; ++k) ASSERT_TRUE(solver.step(dt)) << solver.failure();
  const ParticleStore& s = solver.particles();
  using L = RecordLayout<true, false>;
  PairRecords records;
  records.fill<L, 0>(s, solver.physics().eos.rho0, nullptr, nullptr);
  std::array<int, 4> seen{};  // per kind
  std::size_t wrong_volume = 0, wrong_mask = 0;
  for (std::size_t i = 0; i <= s.size(); ++i) {
    const float* r = records.data() + i * L::fields;
    const std::uint8_t k = s.kind[i];
    ++seen.at(k);
    wrong_volume += r[L::vol] != static_cast<float>(s.mass / s.rho[i]);
    const float mask = (k == kFluidByte || k == kInletByte) ? 1.0f : 0.0f;
    wrong_mask += r[L::diffusion_mask] != mask;
  }
  for (int k = 0; k < 4; ++k) EXPECT_GT(seen[k], 0) << "no particle of kind " << k;
  EXPECT_EQ(wrong_volume, 0u);
  EXPECT_EQ(wrong_mask, 0u);
}

TEST(PairRecords, AvxLanesMatchPortableLanesForEveryScheme) {
  expect_lanes_agree<ModernScheme, false>(Scheme::modern, "modern");
  expect_lanes_agree<ModernScheme, true>(Scheme::modern, "modern");
  expect_lanes_agree<ConventionalScheme, false>(Scheme::conventional, "conventional");
  expect_lanes_agree<PrescribedFlow, false>(Scheme::modern, "prescribed");
}

}  // namespace
}  // namespace adrsph
