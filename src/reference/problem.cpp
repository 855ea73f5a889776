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
  if (!c.reactions.empty())
    throw std::invalid_argument(
        "the reference solves first-order kinetics (species.k) only; this case has " +
        std::to_string(c.reactions.size()) +
        " [[reaction]] table(s), which only the SPH engine takes so far");
  Problem p;
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
