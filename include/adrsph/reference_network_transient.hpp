// The transient mode of the network reference (docs/reference.md, "Transient mode of a
// network"): for each species s of a case's [[species]] tables,
//   dC_s/dt + u(y) dC_s/dx = D_s (C_s,xx + C_s,yy) - sum_r nu_rs R_r(C),
//   C_s(x, y, 0) = c_init,s,   C_s(0, y, t) = C_in,s(t) (species s's [species.feed]),
// dC_s/dn = 0 at the walls and the steady solver's outlet at x = L, on the grid and with the
// cell balances (N1) of the steady network solve (reference_network.hpp), BDF2 in time with
// the single-species mode's feed windows and start (reference_transient.hpp). Each step's
// coupled nonlinear system is solved by a chord iteration (the step matrix of an earlier
// iterate, species by species) with the limiter lagged (deferred
// correction), as the steady network solve does. Its outlet series are the SPH run's
// contract: outlet.csv for the first species, outlet_<name>.csv for the others.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "adrsph/case.hpp"
#include "adrsph/probes.hpp"
#include "adrsph/reference_network.hpp"
#include "adrsph/reference_transient.hpp"

namespace adrsph::reference {

struct NetworkTransientProblem {
  NetworkProblem space;  // species, D, reactions, geometry; the species' c_in are not used
  struct Feed {
    double c_init = 0.0;  // uniform initial C_s
    // int_a^b C_in,s(t) dt; each step takes the feed's mean over a window.
    std::function<double(double a, double b)> inlet_integral;
    double before_start = 0.0;  // C_in,s(0-)
  };
  std::vector<Feed> feeds;  // one per species, in the order of space.species
  double t_end = 1.0;       // [s]; solved to the first sample at or after it
  double sample_interval = 0.01;
};

// The case's network (network_problem_from_case), each species' c_init and [species.feed],
// time.t_end and output.outlet_interval. Throws std::invalid_argument where
// network_problem_from_case does.
NetworkTransientProblem network_transient_problem_from_case(const Case& c);

struct NetworkTransientSolution {
  NetworkSolution final;  // the fields at t_reached
  double t_reached = 0.0;
  std::vector<std::vector<OutletRow>> outlet;  // [species][sample], t = 0, interval, ...
  // Per species, amounts over [0, t_reached] divided by the flow rate (TransientBalance);
  // `reacted` is the net consumption, V sum_r nu_rs R_r summed over the cells (a product's
  // is negative).
  std::vector<TransientBalance> balance;
  TransientReport report;  // `corrections`: iterations (linear solves), all steps
  int factorisations = 0;  // of the step matrix (whole or its species blocks), all steps
  long coupled_steps = 0;  // steps that fell back on the coupled matrix (network_transient.cpp)
};

// Throws std::invalid_argument on bad input (grid, network, feeds, dt, interval, t_end).
NetworkTransientSolution solve_network_transient(const NetworkTransientProblem& p, int nx, int ny,
                                                 const TransientOptions& opt = {});

// DIR/run.json of a network's transient reference: as write_transient_run_json, with
// "species" (names) and "balance" per species.
void write_network_transient_run_json(const std::filesystem::path& file, const Case& c,
                                      const std::vector<std::string>& overrides,
                                      const NetworkTransientSolution& s, double wall_seconds);

}  // namespace adrsph::reference
