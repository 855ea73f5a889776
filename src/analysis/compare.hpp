// The paper's error metrics (docs/benchmark.md, section 4): SPH run against the reference.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "adrsph/probes.hpp"

namespace adrsph::analysis {

// Relative error |C - C_ref| / C_ref on the probe lines, at the run's probe abscissae
// (the reference is interpolated linearly in x if the abscissae differ).
struct LineErrors {
  std::vector<double> x_mm;
  std::vector<double> err_y0, err_yp25, err_ym25, err_mean;
};
LineErrors line_errors(const ProbeTable& run, const ProbeTable& ref);

struct LineSummary {
  const char* name;
  double max = 0.0, mean = 0.0;
};
std::vector<LineSummary> summarise(const LineErrors& e);  // y0, y+2.5, y-2.5, mean

// The paper's table 3 row for a Peclet number (10, 1000, 100000; within 1%).
struct PaperRow {
  double pe;
  double modern[3];  // relative error [-] at x = 25, 50, 100
  double conventional[3];
};
std::optional<PaperRow> paper_table3_row(double pe);

struct StationError {
  double x_mm, c_run, c_ref, rel_error;
  std::optional<double> paper_modern, paper_conventional;
};
std::vector<StationError> station_errors(const StationTable& run, const StationTable& ref,
                                         std::optional<double> pe);

// What the run says of itself (RUN_DIR/run.json): the first "Pe" number and "scheme" string,
// and whether its kinetics are the paper's (no `reactions`, or one first-order reaction
// without zones): the paper's table 3 is beside the run only then.
struct RunInfo {
  std::optional<double> pe;
  std::optional<std::string> scheme;
  bool paper_kinetics = true;
};
RunInfo read_run_info(const std::filesystem::path& run_json);

void write_line_errors_csv(const std::filesystem::path& file, const LineErrors& e);
std::string compare_markdown(const std::string& run_name, const std::string& ref_name,
                             const RunInfo& info, const std::vector<StationError>& stations,
                             const std::vector<LineSummary>& lines);

}  // namespace adrsph::analysis
