// Quintic B-spline (Schoenberg M6) kernel in 2D, support 3h (docs/benchmark.md, section 1).
//   W(q) = sigma [ (3-q)_+^5 - 6 (2-q)_+^5 + 15 (1-q)_+^5 ],  sigma = 7 / (478 pi h^2)
// Written branch-free, (x)_+ = (x + |x|) / 2, so the neighbour loops vectorise
// (std::max stopped g++ 12 from vectorising it: perf/README.md, "Build flags").
#pragma once

#include <cmath>
#include <numbers>
#include <type_traits>

namespace adrsph {

struct QuinticKernel {
  double h = 1.0;
  double inv_h = 1.0;
  double sigma = 0.0;  // 2D normalisation 7 / (478 pi h^2)
  double support = 3.0;

  explicit QuinticKernel(double h_) : h(h_), inv_h(1.0 / h_) {
    sigma = 7.0 / (478.0 * std::numbers::pi * h * h);
    support = 3.0 * h;
  }

  // (x)_+, branch-free. A scalar type takes (x + |x|) / 2 (see the file comment); eight lanes
  // (schemes/simd8.hpp) take max(x, 0), one instruction where the other spelling is three, with
  // the same value (+0 for every x <= 0, -0 included). A NaN gives 0 there, not NaN; the pair's
  // other terms still carry it (the 1 / r of the force pass), so a step with one still fails.
  template <class T>
  static T positive(T v) {
    if constexpr (std::is_floating_point_v<T>) {
      using std::fabs;
      return T(0.5) * (v + fabs(v));
    } else {
      return max(v, T(0));
    }
  }

  // W(r). T = float for the single-precision passes.
  template <class T = double>
  T value(T r) const {
    const T q = r * static_cast<T>(inv_h);
    const T t3 = positive(T(3) - q), t2 = positive(T(2) - q), t1 = positive(T(1) - q);
    const T t3_2 = t3 * t3, t2_2 = t2 * t2, t1_2 = t1 * t1;
    return static_cast<T>(sigma) *
           (t3_2 * t3_2 * t3 - T(6) * t2_2 * t2_2 * t2 + T(15) * t1_2 * t1_2 * t1);
  }

  // dW/dr (<= 0). The passes divide by r themselves, sharing one division between several
  // factors (see interaction_pass.hpp). T = float, or eight lanes (simd8.hpp) in the force pass.
  template <class T = double>
  T derivative(T r) const {
    const T q = r * static_cast<T>(inv_h);
    const T t3 = positive(T(3) - q), t2 = positive(T(2) - q), t1 = positive(T(1) - q);
    const T t3_2 = t3 * t3, t2_2 = t2 * t2, t1_2 = t1 * t1;
    return static_cast<T>(sigma * inv_h) *
           (T(-5) * t3_2 * t3_2 + T(30) * t2_2 * t2_2 - T(75) * t1_2 * t1_2);
  }

  // (dW/dr) / r, so that grad_i W_ij = F(r_ij) * (r_i - r_j). Zero beyond the support and
  // finite at r = 0 (dW/dr vanishes there).
  double gradient_factor(double r) const { return derivative(r) / (r + 1e-30); }

  // (r_ij . grad_i W_ij) / (r_ij^2 + eta^2) = (dW/dr) r / (r^2 + eta^2) at r^2 = r2: the
  // Laplacian weight of the viscous term (eq. 7), the density diffusion (eq. 8) and the species
  // diffusion (eq. 12). The two functions below are its two spellings, kept together: a change
  // of the weight is an edit here, and Kernel.LaplacianWeightSpellingsAgree fails if they part.
  double laplacian_weight(double r2, double eta2) const {
    const double r = std::sqrt(r2);
    return derivative(r) * r / (r2 + eta2);
  }
  // The same weight in the fused force pass (interaction_pass.hpp), which shares one division
  // between its factors: inv = 1 / (r (r^2 + eta^2) s), where s (the pair's density sum there)
  // cancels. dwdr = derivative(r).
  template <class T>
  static T laplacian_weight_shared(T dwdr, T r2, T inv, T s) {
    return dwdr * r2 * inv * s;
  }
};

}  // namespace adrsph
