// `adrsph reference CASE` for a case of several species: the network reference
// (adrsph/reference_network.hpp), written as the one-species reference writes one species.
#pragma once

#include <filesystem>

#include "adrsph/case.hpp"
#include "adrsph/reference.hpp"

namespace adrsph::cli {

struct NetworkRequest {
  int nx = 0, ny = 0;
  bool convergence = false;  // also solve on nx/2 x ny/2 and print the change per species
  std::filesystem::path out_dir;
  reference::SolverOptions solver;
};

// The default grid of a network (docs/reference.md, "Networks"): the coupled factorisation
// of several species costs far more than one species' at the single-species 1600 x 160.
constexpr int kNetworkNx = 800, kNetworkNy = 80;

// Solves, prints a summary per species and writes DIR/probes.csv, stations.csv (the first
// species), probes_<name>.csv, stations_<name>.csv (the others), reference.h5 and
// reference.json of the first species. Returns the exit code (commands.hpp).
int run_network_reference(const NetworkRequest& r, const Case& c);

}  // namespace adrsph::cli
