// The reference for several species (`[[species]]` tables) coupled by a reaction network
// (`[[reaction]]` tables with reactants and products): the steady problem, for each species s,
//   u(y) dC_s/dx = D_s (C_s,xx + C_s,yy) - sum_r nu_rs R_r(C)
// (nu_rs = +1 for a reactant of reaction r, -1 for a product), C_s = c_in,s at x = 0,
// dC_s/dn = 0 at the walls and the outlet, on the grid and with the fluxes of the single-species
// reference (reference.hpp). The coupled system is solved by Newton's method: the Jacobian is
// the upwind transport of every species plus the exact derivative of the reaction terms, the
// limited advective flux is iterated by deferred correction inside the same loop.
#pragma once

#include <string>
#include <vector>

#include "adrsph/case.hpp"
#include "adrsph/reference.hpp"

namespace adrsph::reference {

struct NetworkProblem {
  // Geometry, velocity profile and u_bulk; its D, k, c_in and reactions are not used.
  Problem flow;
  struct Species {
    std::string name;
    double D = 0.0;     // [mm^2/s]
    double c_in = 0.0;  // inlet value
  };
  std::vector<Species> species;
  // Reactants and products by index into `species`; laws of case.hpp (nth_order n >= 1,
  // michaelis_menten km > 0, bimolecular), zones at cell centres.
  std::vector<Reaction> reactions;

  // The single-species Problem of species s (geometry, velocity, D_s, c_in,s, no reactions):
  // what sampling (probe_table, station_table) and the output writers take.
  Problem species_problem(int s) const;
};

// The network of a case: its species in order, its [[reaction]] tables, and species.k (if
// > 0) as a first-order reaction of the first species. Throws std::invalid_argument for a
// rate law the reference does not take (as problem_from_case).
NetworkProblem network_problem_from_case(const Case& c);

struct NetworkSolution {
  Grid grid;
  std::vector<std::vector<double>> c;  // c[s][grid.index(i, j)]
  SolveReport report;                  // Newton iterations in `corrections`
  // The field of species s as a single-species Solution (same grid and report).
  Solution species_solution(int s) const;
};

// Newton's method on the coupled cell balances (src/reference/network_solver.cpp): unknowns
// numbered cell-major, species-minor; J = the upwind transport of every species + the exact
// derivative of the rates, factorised by opt.solver while the change exceeds 0.1 C_scale,
// then kept (chord); the limiter by deferred correction; stops when max |dC| < opt.tolerance
// C_scale (C_scale = the largest c_in, or 1) or after opt.max_corrections iterations.
// `report.residual` is ||F|| / ||b|| of the full limited scheme with the reactions. Throws
// std::invalid_argument for a network it does not take (reaction[i] named: laws as above,
// reactant and product indices, one reactant, or two different ones for bimolecular).
NetworkSolution solve_network_steady(const NetworkProblem& p, int nx, int ny,
                                     const SolverOptions& opt = {});

}  // namespace adrsph::reference
