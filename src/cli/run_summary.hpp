// The readable end-of-run summary printed by `adrsph run`.
#pragma once

#include <filesystem>
#include <ostream>
#include <vector>

#include "adrsph/case.hpp"
#include "adrsph/io/fields_h5.hpp"
#include "adrsph/simulation.hpp"

namespace adrsph::cli {

struct SummaryInfo {
  int threads = 1;
  double wall_s = 0.0;
  std::filesystem::path out_dir;
  std::vector<std::string> files;  // names inside out_dir
};

void print_summary(std::ostream& os, const Case& c, const RunResult& r, const SummaryInfo& s);

}  // namespace adrsph::cli
