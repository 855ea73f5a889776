// The texts of `adrsph rtd` (docs/rtd.md, section 1): rtd.csv, rtd.json and rtd.md. Strings
// only; the command writes them.
#pragma once

#include <string>
#include <vector>

#include "adrsph/case.hpp"
#include "analysis/rtd.hpp"
#include "analysis/rtd_against.hpp"

namespace adrsph::analysis {

// What the reader should know before trusting the figures: moments truncated by the run's
// end, a reacting tracer, no model without diffusion. One sentence each, empty when none.
std::vector<std::string> rtd_warnings(const Rtd& r, const Case& c);

// `against`: the comparison with a transient reference (rtd --against), or none.
// Header t_s,C_out,E_per_s,C_model,C_model_closed,C_reference; the model columns empty where
// there is no model (D = 0), C_reference empty without a reference.
std::string rtd_csv(const Rtd& r, const RtdAgainst* against = nullptr);
// Every figure of the analysis with the case's parameters; NaN as null; "reference" null
// without a reference.
std::string rtd_json(const Rtd& r, const Case& c, const RtdAgainst* against = nullptr);
// The short readable summary (also printed by the command).
std::string rtd_markdown(const Rtd& r, const Case& c, const RtdAgainst* against = nullptr);

}  // namespace adrsph::analysis
