// A run's outlet series against a transient reference's (docs/kinetics.md, "A network in
// time"): per species, the excursion of the flow-weighted outlet mean from its value at t = 0,
// e(t) = C_flow(t) - C_flow(0), the quantity a pulse, a step or a dip share. Pure functions,
// no I/O.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "adrsph/probes.hpp"

namespace adrsph::analysis {

struct OutletSeriesError {
  std::string species;                        // its name ("" for a one-species run)
  std::size_t samples = 0;                    // of the run, all within the reference's times
  double run_area = 0.0, ref_area = 0.0;      // int e dt over the run's samples [mol/m^3 s]
  double area_error = 0.0;                    // run_area / ref_area - 1
  double run_peak = 0.0, ref_peak = 0.0;      // e at the largest |e|
  double run_peak_t = 0.0, ref_peak_t = 0.0;  // [s]
  // int |e_run - e_ref| dt / int |e_ref| dt (the reference interpolated linearly to the
  // run's sample times), and max |e_run - e_ref| / max |e_ref|.
  double l1 = 0.0, max_error = 0.0;
  // C_flow_run / C_flow_ref - 1 at the run's last sample, where the reference's is not 0:
  // an offset of the level a species returns to (a WCSPH run's dilution of a species fed
  // steadily, docs/kinetics.md) that the excursion's integral accumulates over the series.
  std::optional<double> end_offset;
};

// Throws std::invalid_argument when the reference does not cover the run's samples (t = 0
// included), when either has fewer than 3 samples, or when the reference's excursion is 0.
OutletSeriesError outlet_series_error(const std::string& species, const std::vector<OutletRow>& run,
                                      const std::vector<OutletRow>& ref);

// A Markdown table of the species' figures, headed by the run and reference names.
std::string outlet_compare_markdown(const std::string& run_name, const std::string& ref_name,
                                    const std::vector<OutletSeriesError>& rows);

}  // namespace adrsph::analysis
