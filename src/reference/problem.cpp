// The reactor problem of a case (docs/benchmark.md, section 1): parabolic profile with
// u_max = 2 u_bulk.
#include <stdexcept>
#include <string>

#include "adrsph/reference.hpp"

namespace adrsph::reference {

std::function<double(double)> parabolic_profile(double u_max, double half_width) {
  return [u_max, half_width](double y) {
    const double eta = y / half_width;
    return u_max * (1.0 - eta * eta);
  };
}

Problem problem_from_case(const Case& c) {
  if (c.species_count() > 1)
    throw std::invalid_argument(
        "the case has " + std::to_string(c.species_count()) +
        " species: its reference is the network one (network_problem_from_case)");
  // The reaction terms are iterated with a slope bound (reaction_terms.cpp): it must be finite.
  for (std::size_t i = 0; i < c.reactions.size(); ++i) {
    const Reaction& r = c.reactions[i];
    if ((r.law == RateLaw::nth_order && r.order < 1.0) ||
        (r.law == RateLaw::michaelis_menten && !(r.km > 0.0)))
      throw std::invalid_argument(
          "reaction[" + std::to_string(i) +
          "]: the reference takes n-th order kinetics with n >= 1 and Michaelis-Menten with "
          "km > 0 (a rate with an unbounded slope at C = 0 is for the SPH engine only)");
  }
  Problem p;
  p.reactions = c.reactions;
  p.length = c.geometry.length;
  p.half_width = c.geometry.half_width;
  p.D = c.species.D;
  p.k = c.species.k;
  p.c_in = c.species.c_in;
  p.u_bulk = c.fluid.u_bulk;
  p.velocity = parabolic_profile(c.u_max(), c.geometry.half_width);
  return p;
}

const char* to_string(Limiter l) {
  switch (l) {
    case Limiter::upwind:
      return "upwind";
    case Limiter::minmod:
      return "minmod";
    case Limiter::van_leer:
      return "van_leer";
  }
  return "?";
}

const char* to_string(LinearSolver s) {
  switch (s) {
    case LinearSolver::sparse_lu:
      return "SparseLU";
    case LinearSolver::bicgstab_ilut:
      return "BiCGSTAB+IncompleteLUT";
  }
  return "?";
}

}  // namespace adrsph::reference
