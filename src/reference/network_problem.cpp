// The reaction network of a case (reference_network.hpp): its species, the parabolic reactor
// of problem_from_case (docs/benchmark.md, section 1) and its reactions; the single-species
// views of it that sampling and the output writers take; the checks of what the solver takes.
#include <cmath>
#include <stdexcept>
#include <string>

#include "reference/network_system.hpp"

namespace adrsph::reference {
namespace {

[[noreturn]] void bad_reaction(std::size_t i, const std::string& what) {
  throw std::invalid_argument("reaction[" + std::to_string(i) + "]: " + what);
}

}  // namespace

Problem NetworkProblem::species_problem(int s) const {
  const Species& sp = species.at(static_cast<std::size_t>(s));
  Problem p;
  p.length = flow.length;
  p.half_width = flow.half_width;
  p.u_bulk = flow.u_bulk;
  p.velocity = flow.velocity;
  p.D = sp.D;
  p.k = 0.0;
  p.c_in = sp.c_in;
  return p;  // no inlet profile, source or reactions: the network's terms are not linear in C_s
}

NetworkProblem network_problem_from_case(const Case& c) {
  NetworkProblem p;
  p.flow.length = c.geometry.length;
  p.flow.half_width = c.geometry.half_width;
  p.flow.u_bulk = c.fluid.u_bulk;
  p.flow.velocity = parabolic_profile(c.u_max(), c.geometry.half_width);
  p.flow.D = c.species.D;  // unused by the network solve; keeps flow.peclet() that of species 0
  p.flow.k = 0.0;
  p.flow.c_in = c.species.c_in;
  for (int s = 0; s < c.species_count(); ++s) {
    const Case::Species& sp = c.species_at(s);
    p.species.push_back({sp.name, sp.D, sp.c_in});
  }
  p.reactions = c.reactions;
  // species.k: first-order decay of the first species, R = k C_0, no product. Appended, so
  // that reaction[i] of a message is the case's i-th [[reaction]] table.
  if (c.species.k > 0.0) {
    Reaction decay;
    decay.law = RateLaw::first_order;
    decay.k = c.species.k;
    decay.reactants = {0};
    decay.products.clear();
    p.reactions.push_back(decay);
  }
  detail::check_network(p);
  return p;
}

Solution NetworkSolution::species_solution(int s) const {
  Solution out;
  out.grid = grid;
  out.c = c.at(static_cast<std::size_t>(s));
  out.report = report;
  return out;
}

namespace detail {

void check_network(const NetworkProblem& p) {
  const int n = static_cast<int>(p.species.size());
  if (n < 1) throw std::invalid_argument("reference: the network has no species");
  for (int s = 0; s < n; ++s)
    if (!(p.species[static_cast<std::size_t>(s)].D >= 0.0))
      throw std::invalid_argument("reference: species[" + std::to_string(s) + "] needs D >= 0");
  auto valid = [n](int s) { return s >= 0 && s < n; };
  for (std::size_t i = 0; i < p.reactions.size(); ++i) {
    const Reaction& r = p.reactions[i];
    // Newton needs dR/dC: bounded at C = 0 (problem_from_case's rule, the same message).
    if ((r.law == RateLaw::nth_order && !(r.order >= 1.0)) ||
        (r.law == RateLaw::michaelis_menten && !(r.km > 0.0)))
      bad_reaction(i,
                   "the reference takes n-th order kinetics with n >= 1 and Michaelis-Menten with "
                   "km > 0 (a rate with an unbounded slope at C = 0 is for the SPH engine only)");
    if (!(r.k >= 0.0) || !std::isfinite(r.k)) bad_reaction(i, "needs a finite k >= 0");
    const std::size_t want = r.law == RateLaw::bimolecular ? 2 : 1;
    if (r.reactants.size() != want)
      bad_reaction(i, r.law == RateLaw::bimolecular ? "bimolecular needs two reactants"
                                                    : "needs exactly one reactant");
    for (int s : r.reactants)
      if (!valid(s)) bad_reaction(i, "reactant index " + std::to_string(s) + " is no species");
    for (int s : r.products)
      if (!valid(s)) bad_reaction(i, "product index " + std::to_string(s) + " is no species");
    if (want == 2 && r.reactants[0] == r.reactants[1])
      bad_reaction(i, "bimolecular needs two different reactants");
    for (const Reaction::Zone& z : r.zones)
      if (!(z.factor >= 0.0)) bad_reaction(i, "a zone factor must be >= 0");
  }
}

}  // namespace detail
}  // namespace adrsph::reference
