// The particle store's field list (particle_store.hpp): every array it lists is sized with the
// store, and every carried array follows its particle through a re-sort.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <random>
#include <set>
#include <type_traits>
#include <vector>

#include "particles/particle_store.hpp"

namespace adrsph {
namespace {

TEST(ParticleStore, PermuteCarriesEveryListedField) {
  ParticleStore s;
  s.mass = 1.0;
  const std::size_t n = 50;
  for (std::size_t i = 0; i < n; ++i) s.push_back(0.0, 0.0, 0.0, 0.0, 1.0, 0.0, Kind::fluid);
  // A value that names the particle (its index) in every carried array.
  std::size_t fields = 0;
  ParticleStore::for_each_field(s, [&](auto& a, ParticleStore::Role role, const char*) {
    EXPECT_EQ(a.size(), n + 1);  // the padding particle too
    if (!ParticleStore::carried(role)) return;
    ++fields;
    using T = typename std::decay_t<decltype(a)>::value_type;
    for (std::size_t i = 0; i < n; ++i) a[i] = static_cast<T>(i);
  });
  // What a particle carries between steps: its state, its kind, and what derives from the kind
  // or is read before it is recomputed (p, V at the first evaluation after a re-sort).
  std::set<const void*> carried;
  ParticleStore::for_each_field(s, [&](auto& a, ParticleStore::Role role, const char*) {
    if (ParticleStore::carried(role)) carried.insert(&a);
  });
  for (const void* a : {static_cast<const void*>(&s.x), static_cast<const void*>(&s.y),
                        static_cast<const void*>(&s.vx), static_cast<const void*>(&s.vy),
                        static_cast<const void*>(&s.rho), static_cast<const void*>(&s.c),
                        static_cast<const void*>(&s.kind), static_cast<const void*>(&s.p),
                        static_cast<const void*>(&s.fluid_side)})
    EXPECT_EQ(carried.count(a), 1u);
  EXPECT_EQ(fields, carried.size());
  // Keep every other particle, in reverse order.
  std::vector<std::uint32_t> order;
  for (std::size_t i = n; i-- > 0;)
    if (i % 2 == 0) order.push_back(static_cast<std::uint32_t>(i));
  s.permute(order);
  ASSERT_EQ(s.size(), order.size());
  ParticleStore::for_each_field(s, [&](auto& a, ParticleStore::Role role, const char*) {
    EXPECT_EQ(a.size(), order.size() + 1);
    if (!ParticleStore::carried(role)) return;
    using T = typename std::decay_t<decltype(a)>::value_type;
    for (std::size_t k = 0; k < order.size(); ++k) {
      const std::size_t i = order[k];
      EXPECT_EQ(a[k], static_cast<T>(i)) << "field of value size " << sizeof(T);
    }
  });
  // The padding particle is reset after the permutation: far away, a wall (no diffusion, not
  // sampled by the boundaries), no species.
  EXPECT_GT(s.x[s.size()], 1e11);
  EXPECT_EQ(s.kind[s.size()], kWallByte);
  EXPECT_EQ(s.diffusion_mask(s.size()), 0.0f);
  EXPECT_EQ(s.fluid_side[s.size()], 0.0f);
  EXPECT_EQ(s.c[s.size()], 0.0);
}

// The in-place permutation walks each cycle from its leader: random orders (fixed points,
// short and long cycles, removed particles) and the shift a re-sort typically makes (one
// particle moved to another cell moves every particle between by one place).
TEST(ParticleStore, PermuteInPlaceMatchesAGatherForAnyOrder) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 200; ++trial) {
    const std::size_t n = 1 + rng() % 300;
    ParticleStore s;
    s.mass = 1.0;
    for (std::size_t i = 0; i < n; ++i)
      s.push_back(static_cast<double>(i), -static_cast<double>(i), 0.0, 0.0, 1.0, 0.5 * i,
                  Kind::fluid);
    std::vector<std::uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    if (trial % 4 == 0) {  // a shift: particle a moves to place b
      const std::size_t a = rng() % n, b = rng() % n;
      const std::uint32_t moved = order[a];
      order.erase(order.begin() + static_cast<std::ptrdiff_t>(a));
      order.insert(order.begin() + static_cast<std::ptrdiff_t>(b), moved);
    } else {
      std::shuffle(order.begin(), order.end(), rng);
    }
    order.resize(n - rng() % (n / 4 + 1));  // the ones cut off are removed
    s.permute(order);
    ASSERT_EQ(s.size(), order.size());
    for (std::size_t k = 0; k < order.size(); ++k) {
      ASSERT_EQ(s.x[k], static_cast<double>(order[k])) << "trial " << trial << ", place " << k;
      ASSERT_EQ(s.y[k], -static_cast<double>(order[k]));
      ASSERT_EQ(s.c[k], 0.5 * order[k]);
    }
  }
}

// The first evaluation's rates become the first-stage rates by a swap of buffers: the
// values move, nothing is copied, and only the arrays the scheme uses take part.
TEST(ParticleStore, FirstStageRatesAreSwappedInNotCopied) {
  ParticleStore s;
  s.set_needs({true, true, true, 0, false});  // the modern scheme, rates of C kept
  s.mass = 1.0;
  s.push_back(1.0, 2.0, 3.0, 4.0, 5.0, 6.0, Kind::fluid);
  s.ax[0] = 1.5f, s.ay[0] = 2.5f, s.drho[0] = 3.5f, s.dc[0] = 4.5f, s.sx[0] = 5.5f, s.sy[0] = 6.5f;
  const float* ax_buffer = s.ax.data();
  s.keep_first_stage_rates();
  EXPECT_EQ(s.ax_first.data(), ax_buffer);
  EXPECT_EQ(s.ax_first[0], 1.5f);
  EXPECT_EQ(s.ay_first[0], 2.5f);
  EXPECT_EQ(s.drho_first[0], 3.5f);
  EXPECT_EQ(s.dc_first[0], 4.5f);
  EXPECT_EQ(s.sx_first[0], 5.5f);
  EXPECT_EQ(s.sy_first[0], 6.5f);
  EXPECT_TRUE(s.c_start.empty());
  // Sub-cycled diffusion keeps C's start value instead of its rate; a prescribed flow has
  // neither velocity nor density rates.
  ParticleStore p;
  p.set_needs({false, false, false, 0, true});
  p.push_back(1.0, 2.0, 3.0, 0.0, 5.0, 6.0, Kind::fluid);
  p.dc[0] = 7.5f;
  p.keep_first_stage_rates();
  EXPECT_EQ(p.dc[0], 7.5f);  // not swapped: C is undone from c_start
  EXPECT_EQ(p.c_start.size(), 2u);
  EXPECT_TRUE(p.dc_first.empty());
  EXPECT_TRUE(p.ax.empty() && p.ax_first.empty() && p.drho_first.empty() && p.sx_first.empty());
}

}  // namespace
}  // namespace adrsph
