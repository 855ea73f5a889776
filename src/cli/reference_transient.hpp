// `adrsph reference CASE --transient`: the transient finite-volume reference of a case
// (docs/reference.md, "Transient mode"), written as a run directory that `adrsph rtd` reads.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "adrsph/case.hpp"
#include "adrsph/reference.hpp"

namespace adrsph::cli {

struct TransientRequest {
  std::filesystem::path case_file;     // copied to DIR/case.toml
  std::vector<std::string> overrides;  // the --set values, recorded in DIR/run.json
  int nx = 0, ny = 0;
  double dt = 0.0;  // [s]; 0: default_transient_dt()
  std::filesystem::path out_dir;
  reference::LinearSolver solver = reference::LinearSolver::sparse_lu;
  reference::Limiter limiter = reference::Limiter::van_leer;
};

// Solves, prints a summary and writes DIR/outlet.csv, DIR/case.toml and DIR/run.json.
// Returns the exit code (commands.hpp): 2 when the case has no outlet interval.
int run_transient_reference(const TransientRequest& r, const Case& c);

}  // namespace adrsph::cli
