#include "analysis/dispersion_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace adrsph::analysis {
namespace {

// Below this std::erfc is far from underflow (erfc(20) ~ 5e-176) and exp(x^2) from overflow.
constexpr double kScaledErfcDirect = 20.0;

// Phi(z), the standard normal CDF.
double normal_cdf(double z) {
  return 0.5 * std::erfc(-z / std::numbers::sqrt2);
}

// integral of F(t - s) ds over [a, b] (b > a) by Simpson's rule on steps of at most
// `step`: F is smooth (all its derivatives vanish at 0+), so the rule converges as step^4.
double integral_of_cdf(const InverseGaussian& e, double t, double a, double b, double step) {
  b = std::min(b, t);  // F(t - s) = 0 for s >= t
  if (!(b > a)) return 0.0;
  constexpr long kMaxIntervals = 1L << 14;
  long n = static_cast<long>(std::ceil((b - a) / step));
  n = std::clamp(n + (n % 2), 2L, kMaxIntervals);
  const double h = (b - a) / static_cast<double>(n);
  double sum = cdf(e, t - a) + cdf(e, t - b);
  for (long i = 1; i < n; ++i)
    sum += (i % 2 ? 4.0 : 2.0) * cdf(e, t - (a + h * static_cast<double>(i)));
  return sum * h / 3.0;
}

}  // namespace

double scaled_erfc(double x) {
  if (x < kScaledErfcDirect) return std::exp(x * x) * std::erfc(x);
  // The asymptotic series erfc(x) e^{x^2} = 1/(x sqrt(pi)) sum_n (-1)^n (2n-1)!! / (2x^2)^n:
  // its terms shrink by (2n-1)/(2x^2) < 0.05 for the first ten at x >= 20, so ten terms
  // leave less than 1e-17 (the smallest term, near n = x^2, is ~e^{-x^2}).
  const double inv = 1.0 / (2.0 * x * x);
  double term = 1.0, sum = 1.0;
  for (int n = 1; n <= 10; ++n) {
    term *= -(2.0 * n - 1.0) * inv;
    sum += term;
  }
  return sum / (x * std::sqrt(std::numbers::pi));
}

double pdf(const InverseGaussian& e, double t) {
  if (!(t > 0.0)) return 0.0;
  const double d = t - e.mean;
  return std::sqrt(e.shape / (2.0 * std::numbers::pi * t * t * t)) *
         std::exp(-e.shape * d * d / (2.0 * e.mean * e.mean * t));
}

double cdf(const InverseGaussian& e, double t) {
  if (!(t > 0.0)) return 0.0;
  const double r = std::sqrt(e.shape / t);
  const double z1 = r * (t / e.mean - 1.0), z2 = r * (t / e.mean + 1.0);
  // exp(2 lambda/mu) Phi(-z2) = exp(2 lambda/mu - z2^2/2) scaled_erfc(z2/sqrt2) / 2, and
  // z2^2 - z1^2 = 4 lambda/mu, so the combined exponent is -z1^2/2 <= 0: no overflow, and no
  // loss to erfc's underflow (at t = mu this term is ~1/sqrt(4 pi Pe_L), not negligible).
  const double second = 0.5 * std::exp(-0.5 * z1 * z1) * scaled_erfc(z2 / std::numbers::sqrt2);
  return std::min(1.0, normal_cdf(z1) + second);
}

double mean_velocity(const Case& c) {
  return 2.0 / 3.0 * c.u_max();
}

TaylorAris taylor_aris(const Case& c) {
  const double u = mean_velocity(c), length = c.geometry.length;
  const double r = c.geometry.half_width, d = c.species.D;
  TaylorAris m;
  // Plane Poiseuille flow, gap 2R: K = D + U^2 (2R)^2 / (210 D) (Taylor 1953, Aris 1956;
  // the same K = D (1 + (2/105) (U R / D)^2) as docs/benchmark.md, section 5).
  m.dispersion = d + u * u * (2.0 * r) * (2.0 * r) / (210.0 * d);
  m.peclet_length = u * length / m.dispersion;
  m.space_time = length / u;
  m.applicability = m.space_time * d / (r * r);
  m.residence = {length / u, length * length / (2.0 * m.dispersion)};
  return m;
}

double model_outlet_excess(const Case::Species& s, const InverseGaussian& e, double t) {
  const auto& f = s.feed;
  if (f.shape == FeedShape::pulse)
    return (s.c_in - f.base) * (cdf(e, t - f.t0) - cdf(e, t - f.t0 - f.width));
  if (f.shape != FeedShape::table) return 0.0;
  // (g_in * E)(t) = integral g_in(s) E(t - s) ds = integral g_in'(s) F(t - s) ds: by parts,
  // with g_in = 0 at the table's ends (check_rtd_feed() in analysis/rtd.hpp). g_in' is the slope of
  // each segment, so a nearly vertical edge of height dC contributes dC F(t - s_edge), as in
  // the pulse formula. Simpson's steps of sigma/8 resolve F's rise (width ~ sigma).
  const double step = std::sqrt(e.variance()) / 8.0;
  double sum = 0.0;
  for (std::size_t i = 1; i < f.table.size(); ++i) {
    const double ta = f.table[i - 1][0], tb = f.table[i][0];
    const double slope = (f.table[i][1] - f.table[i - 1][1]) / (tb - ta);
    if (slope != 0.0) sum += slope * integral_of_cdf(e, t, ta, tb, step);
  }
  return sum;
}

}  // namespace adrsph::analysis
