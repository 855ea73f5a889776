// What the force pass reads of a neighbour j, packed into one record of floats per particle,
// refreshed at the start of each pass (interaction_pass.hpp). The pair loop then loads eight
// neighbours' records whole and transposes them into one vector per field (simd8.hpp), where
// reading each of ~10 arrays one float or double at a time took most of the pass
// (perf/README.md, section 3.20).
//
// A double that the pass differences (position, velocity, concentration: neighbour
// differences are ~1e-4 of the values) is stored as two floats, hi = float(v) and
// lo = float(v - hi). Then v_i - v_j = (hi_i - hi_j) + (lo_i - lo_j): the first difference is
// exact for close values (Sterbenz), the second carries the ~1e-8 relative rest, and the sum is
// rounded once, as float(v_i - v_j) taken in double was before. The density enters as
// rho_excess = float(rho - rho0): the excess is ~1e-2 rho0 at most, so its float rounding is
// ~1e-9 rho0, far below the neighbour differences (~1e-4 rho0) the pass takes of it.
//
// Layouts (field indices, by what the scheme needs; `Flow`: momentum schemes):
//   Flow:    x_hi y_hi x_lo y_lo vx_hi vy_hi vx_lo vy_lo | c_hi c_lo rho_excess p vol
//            diffusion_mask extra0 extra1   (extra: fluid_side for the ALE term; the
//            conventional scheme's predicted displacement d_x, d_y)
//   no Flow: x_hi y_hi x_lo y_lo c_hi c_lo vol diffusion_mask
//   Network: then c_hi c_lo of each further species (ParticleStore::c_more), two spare.
#pragma once

#include <algorithm>
#include <cstddef>
#include <new>
#include <vector>

#include "particles/particle_store.hpp"
#include "schemes/pass_context.hpp"

namespace adrsph {

template <bool Flow, bool Network>
struct RecordLayout {
  static constexpr bool flow = Flow, network = Network;
  static constexpr int x_hi = 0, y_hi = 1, x_lo = 2, y_lo = 3;
  static constexpr int vx_hi = 4, vy_hi = 5, vx_lo = 6, vy_lo = 7;  // Flow only
  static constexpr int c_hi = Flow ? 8 : 4, c_lo = c_hi + 1;
  static constexpr int rho_excess = 10, p = 11;  // Flow only
  static constexpr int vol = Flow ? 12 : 6, diffusion_mask = vol + 1;
  static constexpr int extra0 = 14, extra1 = 15;  // Flow only
  static constexpr int more = Flow ? 16 : 8;      // c_hi, c_lo of species e at more + 2 e
  static constexpr int fields = more + (Network ? 8 : 0);
  static_assert(ParticleStore::kMaxMore * 2 <= 8, "the network block holds three species");
};

// v = hi + lo with both floats (see the file comment).
inline void split_hi_lo(double v, float& hi, float& lo) {
  hi = static_cast<float>(v);
  lo = static_cast<float>(v - static_cast<double>(hi));
}

// Records start on a cache line, so that a 64-byte record is one line, never two. (Not shown to
// matter on the host of perf/README.md, 3.20: aligned and unaligned builds timed alike there.)
template <class T>
struct CacheLineAllocator {
  using value_type = T;
  static constexpr std::align_val_t kAlign{64};
  CacheLineAllocator() = default;
  template <class U>
  CacheLineAllocator(const CacheLineAllocator<U>&) {}  // NOLINT: rebinding
  T* allocate(std::size_t n) { return static_cast<T*>(::operator new(n * sizeof(T), kAlign)); }
  void deallocate(T* p, std::size_t) { ::operator delete(p, kAlign); }
  friend bool operator==(const CacheLineAllocator&, const CacheLineAllocator&) { return true; }
};

class PairRecords {
 public:
  // Fill the records of every particle, the padding particle included, from the state the
  // density and boundary passes of this evaluation left (rho0: the rest density). `extra0`,
  // `extra1`: per-particle floats for the Flow layout's two spare fields, the first kExtras of them
  // given (the others are set to 0). A compile-time count: a test of the pointers inside the loop
  // made g++ use masked loads, which tripled the fill's time (perf/README.md, section 3.20).
  template <class Layout, int kExtras>
  void fill(const ParticleStore& s, double rho0, const float* extra0, const float* extra1) {
    static_assert(kExtras == 0 || Layout::flow, "only the Flow layout has spare fields");
    const std::size_t n = s.size() + 1;
    // Grown as the store grows (~3% headroom, not std::vector's doubling), and to the size
    // they had before a release() in mid-run: the particle count varies by a few tens as the
    // buffers feed and drain, and refilling at the smaller count would double the block at
    // the next larger one.
    if (n * Layout::fields > data_.capacity())
      data_.reserve(std::max(ParticleStore::grown_capacity(n) * Layout::fields, kept_capacity_));
    kept_capacity_ = 0;
    data_.resize(n * Layout::fields);
    float* out = data_.data();
    [[maybe_unused]] const int more = s.needs().more_species;
#pragma omp parallel for schedule(static)
    for (std::size_t i = 0; i < n; ++i) {
      float* r = out + i * Layout::fields;
      split_hi_lo(s.x[i], r[Layout::x_hi], r[Layout::x_lo]);
      split_hi_lo(s.y[i], r[Layout::y_hi], r[Layout::y_lo]);
      split_hi_lo(s.c[i], r[Layout::c_hi], r[Layout::c_lo]);
      r[Layout::vol] = s.volume(i);
      r[Layout::diffusion_mask] = ParticleStore::diffusion_mask_of(s.kind[i]);
      if constexpr (Layout::flow) {
        split_hi_lo(s.vx[i], r[Layout::vx_hi], r[Layout::vx_lo]);
        split_hi_lo(s.vy[i], r[Layout::vy_hi], r[Layout::vy_lo]);
        r[Layout::rho_excess] = static_cast<float>(s.rho[i] - rho0);
        r[Layout::p] = s.p[i];
        r[Layout::extra0] = kExtras > 0 ? extra0[i] : 0.0f;
        r[Layout::extra1] = kExtras > 1 ? extra1[i] : 0.0f;
      }
      if constexpr (Layout::network) {
        for (int f = Layout::more; f < Layout::fields; ++f) r[f] = 0.0f;  // unused species: 0
        for (int e = 0; e < more; ++e)
          split_hi_lo(s.c_more[e][i], r[Layout::more + 2 * e], r[Layout::more + 2 * e + 1]);
      }
    }
  }
  const float* data() const {
    return data_.data();
  }
  std::size_t bytes() const {
    return data_.capacity() * sizeof(float);
  }
  // Give the records back; the next fill takes the capacity they had.
  void release() {
    kept_capacity_ = data_.capacity();
    std::vector<float, CacheLineAllocator<float>>().swap(data_);
  }

 private:
  std::size_t kept_capacity_ = 0;
  std::vector<float, CacheLineAllocator<float>> data_;
};

}  // namespace adrsph
