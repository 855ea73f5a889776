// Eight pairs at once: a vector of eight floats with the operators the pair formulas use, so
// that the templates of the pair terms (momentum.hpp, continuity.hpp, species_rate.hpp and the
// kernel) run on the eight lanes of the force pass unchanged (interaction_pass.hpp), and the
// transposition that turns eight neighbours' records into one vector per field
// (pair_records.hpp).
//
// Two implementations of one interface: `Avx8` (AVX registers; compiled when the target has
// AVX, as the default -march=x86-64-v3 does) and `Portable8` (eight floats in an array, loops
// the compiler vectorises for whatever the target has). `F8` is the first of them the target
// allows. Both are always declared where they can be, so that a test runs the pass with each.
#pragma once

#include <cmath>
#include <cstddef>

#if defined(__AVX__)
#include <immintrin.h>
#endif

namespace adrsph::simd {

// Eight floats in an array: the reference implementation, and the one a target without AVX uses.
struct Portable8 {
  float v[8];
  Portable8() = default;
  Portable8(float a) {  // NOLINT: a scalar broadcasts, as in the pair formulas' T(2) * x
    for (float& e : v) e = a;
  }
  Portable8(double a) : Portable8(static_cast<float>(a)) {}
  Portable8(int a) : Portable8(static_cast<float>(a)) {}
  template <class Op>
  static Portable8 each(const Portable8& a, const Portable8& b, Op op) {
    Portable8 r;
    for (int k = 0; k < 8; ++k) r.v[k] = op(a.v[k], b.v[k]);
    return r;
  }
  friend Portable8 operator+(Portable8 a, Portable8 b) {
    return each(a, b, [](float p, float q) { return p + q; });
  }
  friend Portable8 operator-(Portable8 a, Portable8 b) {
    return each(a, b, [](float p, float q) { return p - q; });
  }
  friend Portable8 operator*(Portable8 a, Portable8 b) {
    return each(a, b, [](float p, float q) { return p * q; });
  }
  friend Portable8 operator/(Portable8 a, Portable8 b) {
    return each(a, b, [](float p, float q) { return p / q; });
  }
  friend Portable8 operator-(Portable8 a) { return Portable8(0.0f) - a; }
  Portable8& operator+=(Portable8 b) { return *this = *this + b; }
  friend Portable8 fabs(Portable8 a) {
    return each(a, a, [](float p, float) { return std::fabs(p); });
  }
  friend Portable8 sqrt(Portable8 a) {
    return each(a, a, [](float p, float) { return std::sqrt(p); });
  }
  friend Portable8 max(Portable8 a, Portable8 b) {
    return each(a, b, [](float p, float q) { return p > q ? p : q; });
  }
  void store(float* out) const {
    for (int k = 0; k < 8; ++k) out[k] = v[k];
  }
  friend float sum(Portable8 a) {
    float s = 0.0f;
    for (float e : a.v) s += e;
    return s;
  }
  // out[f] holds field f of the eight records (lane k: records[k][first + f]), f = 0..7.
  static void transpose(const float* const records[8], int first, Portable8 out[8]) {
    for (int f = 0; f < 8; ++f)
      for (int k = 0; k < 8; ++k) out[f].v[k] = records[k][first + f];
  }
};

#if defined(__AVX__)
// Eight floats in one AVX register.
struct Avx8 {
  __m256 v;
  Avx8() = default;
  Avx8(__m256 a) : v(a) {}                                      // NOLINT
  Avx8(float a) : v(_mm256_set1_ps(a)) {}                       // NOLINT: broadcast
  Avx8(double a) : v(_mm256_set1_ps(static_cast<float>(a))) {}  // NOLINT
  Avx8(int a) : v(_mm256_set1_ps(static_cast<float>(a))) {}     // NOLINT
  friend Avx8 operator+(Avx8 a, Avx8 b) { return _mm256_add_ps(a.v, b.v); }
  friend Avx8 operator-(Avx8 a, Avx8 b) { return _mm256_sub_ps(a.v, b.v); }
  friend Avx8 operator*(Avx8 a, Avx8 b) { return _mm256_mul_ps(a.v, b.v); }
  friend Avx8 operator/(Avx8 a, Avx8 b) { return _mm256_div_ps(a.v, b.v); }
  friend Avx8 operator-(Avx8 a) { return _mm256_xor_ps(a.v, _mm256_set1_ps(-0.0f)); }
  Avx8& operator+=(Avx8 b) { return *this = *this + b; }
  friend Avx8 fabs(Avx8 a) { return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), a.v); }
  friend Avx8 sqrt(Avx8 a) { return _mm256_sqrt_ps(a.v); }
  friend Avx8 max(Avx8 a, Avx8 b) { return _mm256_max_ps(a.v, b.v); }
  void store(float* out) const { _mm256_storeu_ps(out, v); }
  friend float sum(Avx8 a) {
    const __m128 h = _mm_add_ps(_mm256_castps256_ps128(a.v), _mm256_extractf128_ps(a.v, 1));
    const __m128 q = _mm_add_ps(h, _mm_movehl_ps(h, h));
    return _mm_cvtss_f32(_mm_add_ss(q, _mm_shuffle_ps(q, q, 1)));
  }
  // As Portable8::transpose: 16 loads of four fields and 16 shuffles, where eight fields
  // gathered one float at a time take 64 loads and as many inserts.
  static void transpose(const float* const records[8], int first, Avx8 out[8]) {
    __m256 r[8];  // r[k] = [fields 0-3 of record k | of record k + 4]; r[k + 4]: fields 4-7
    for (int k = 0; k < 4; ++k)
      for (int half = 0; half < 2; ++half)
        r[k + 4 * half] = _mm256_insertf128_ps(
            _mm256_castps128_ps256(_mm_loadu_ps(records[k] + first + 4 * half)),
            _mm_loadu_ps(records[k + 4] + first + 4 * half), 1);
    for (int half = 0; half < 2; ++half) {
      const __m256* q = r + 4 * half;
      const __m256 t0 = _mm256_unpacklo_ps(q[0], q[1]), t1 = _mm256_unpackhi_ps(q[0], q[1]);
      const __m256 t2 = _mm256_unpacklo_ps(q[2], q[3]), t3 = _mm256_unpackhi_ps(q[2], q[3]);
      out[4 * half + 0] = _mm256_shuffle_ps(t0, t2, 0x44);
      out[4 * half + 1] = _mm256_shuffle_ps(t0, t2, 0xEE);
      out[4 * half + 2] = _mm256_shuffle_ps(t1, t3, 0x44);
      out[4 * half + 3] = _mm256_shuffle_ps(t1, t3, 0xEE);
    }
  }
};
using F8 = Avx8;
#else
using F8 = Portable8;
#endif

}  // namespace adrsph::simd
