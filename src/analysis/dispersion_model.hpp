// The axial-dispersion model of the channel's residence-time distribution (docs/rtd.md,
// section 5): Taylor-Aris dispersion in plane Poiseuille flow, the inverse Gaussian E(t) of a
// 1D dispersive medium fed at x = 0, and the outlet response it predicts for a case's feed.
#pragma once

#include <vector>

#include "adrsph/case.hpp"

namespace adrsph::analysis {

// exp(x^2) erfc(x) for x >= 0, finite where erfc(x) underflows (x > 26): the inverse Gaussian
// CDF multiplies erfc of a large argument by exp(Pe_L), which alone overflows.
double scaled_erfc(double x);

// The inverse Gaussian IG(mu, lambda): the first-passage time density at x = L of
// dC/dt + U dC/dx = K d2C/dx2 on x > 0 with a Dirichlet pulse at x = 0 (docs/rtd.md, section 5):
//   E(t) = L / sqrt(4 pi K t^3) exp(-(L - U t)^2 / (4 K t))
//        = sqrt(lambda / (2 pi t^3)) exp(-lambda (t - mu)^2 / (2 mu^2 t)),
// mu = L / U, lambda = L^2 / (2 K); mean mu, variance mu^3 / lambda = 2 K L / U^3.
struct InverseGaussian {
  double mean = 1.0;   // mu [s]
  double shape = 1.0;  // lambda [s]
  double variance() const { return mean * mean * mean / shape; }
};
double pdf(const InverseGaussian& e, double t);
// F(t) = Phi(sqrt(lambda/t) (t/mu - 1)) + exp(2 lambda/mu) Phi(-sqrt(lambda/t) (t/mu + 1)),
// 0 for t <= 0; the second term evaluated without overflow for any Pe_L = 2 lambda / mu.
double cdf(const InverseGaussian& e, double t);

// The mean velocity the channel's flow delivers: the profile u(y) = u_max (1 - (y/R)^2) with
// the benchmark's u_max = 2 u_bulk averages to 2/3 u_max = 4/3 u_bulk over the section
// (docs/benchmark.md, section 1). The flow rate per unit depth is Q = 2 R U.
double mean_velocity(const Case& c);

// Taylor-Aris dispersion between walls 2R apart (docs/rtd.md, section 5):
//   K = D + U^2 (2R)^2 / (210 D),  Pe_L = U L / K.
// It describes the outlet once transverse diffusion has mixed the section, i.e. when the
// transverse mixing time R^2 / D is well below the space time tau = L / U.
struct TaylorAris {
  double dispersion = 0.0;     // K [mm^2/s]
  double peclet_length = 0.0;  // Pe_L = U L / K
  double space_time = 0.0;     // tau = V / Q = L / U [s]
  double applicability = 0.0;  // tau D / R^2: the model applies when >= kApplies
  InverseGaussian residence;   // E(t) of the vessel
  static constexpr double kApplies = 10.0;
  bool applies() const { return applicability >= kApplies; }
};
// Needs D > 0 (K is unbounded without diffusion).
TaylorAris taylor_aris(const Case& c);

// The model's outlet excess over `species.feed.base` at time t: the feed's excess convolved
// with E. A pulse: (c_in - base) [F(t - t0) - F(t - t0 - width)]. A table: the convolution
// integrated by parts onto F (the excess is 0 at the table's ends), sum over segments of
// slope_j * integral over the segment of F(t - s) ds, by Simpson's rule. Other feeds: 0.
double model_outlet_excess(const Case::Species& s, const InverseGaussian& e, double t);

// The same dispersion on the channel's own length and boundary conditions (docs/rtd.md,
// section 6): the inlet held at the feed, C(0, t) = C_in(t), as the inflow buffer holds it,
// and no dispersive flux through x = L, as the outflow buffer takes no part in the diffusion.
// Unlike the semi-infinite medium of the inverse Gaussian, tracer cannot disperse past the
// outlet and come back, and it diffuses back out through the inlet once the pulse is over:
// at Pe_L ~ 10 the mean residence time falls several per cent below V/Q.
// Finite volumes (central fluxes, cells with U h / K <= 1/2) and BDF2 steps far finer than
// the feed's features; returns the outlet excess C(L, t) - base at `times` (increasing).
std::vector<double> closed_outlet_excess(const Case& c, const TaylorAris& m,
                                         const std::vector<double>& times);

}  // namespace adrsph::analysis
