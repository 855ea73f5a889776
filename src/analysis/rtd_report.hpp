// The texts of `adrsph rtd` (docs/rtd.md, section 1): rtd.csv, rtd.json and rtd.md. Strings
// only; the command writes them.
#pragma once

#include <string>
#include <vector>

#include "adrsph/case.hpp"
#include "analysis/rtd.hpp"

namespace adrsph::analysis {

// What the reader should know before trusting the figures: moments truncated by the run's
// end, a reacting tracer, no model without diffusion. One sentence each, empty when none.
std::vector<std::string> rtd_warnings(const Rtd& r, const Case& c);

// Header t_s,C_out,E_per_s,C_model; C_model empty where there is no model (D = 0).
std::string rtd_csv(const Rtd& r);
// Every figure of the analysis with the case's parameters; NaN as null.
std::string rtd_json(const Rtd& r, const Case& c);
// The short readable summary (also printed by the command).
std::string rtd_markdown(const Rtd& r, const Case& c);

}  // namespace adrsph::analysis
