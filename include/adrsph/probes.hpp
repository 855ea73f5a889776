// The probe contract shared by `run`, `reference` and `compare`:
// probes.csv  header x_mm,C_y0,C_y+2.5,C_y-2.5,C_mean  (x = 0.5, 1.0, ..., length)
// stations.csv header x_mm,C_mean                      (x = 25, 50, 100)
#pragma once

#include <filesystem>
#include <vector>

namespace adrsph {

struct ProbeTable {
  std::vector<double> x_mm;
  std::vector<double> c_y0, c_yp25, c_ym25;  // C on the lines y = 0, +2.5, -2.5
  std::vector<double> c_mean;                // section average over y in [-R, R]
};

struct StationTable {
  std::vector<double> x_mm;
  std::vector<double> c_mean;
};

// Probe abscissae: 0.5, 1.0, ..., length (step 0.5 mm).
std::vector<double> probe_x_positions(double length);
// Station abscissae of the paper's table 3: 25, 50, 100 (scaled to length/100 if not 100).
std::vector<double> station_x_positions(double length);

void write_probes_csv(const std::filesystem::path& file, const ProbeTable& t);
void write_stations_csv(const std::filesystem::path& file, const StationTable& t);
// One probe check of a run: the section averages at the stations and the steady test's
// change measure (infinity until it has enough samples).
struct HistoryRow {
  double t = 0.0;
  std::vector<double> stations;  // C_mean at station_x_positions()
  double steady_change = 0.0;
};
// history.csv: header t_s,C_mean_x25,C_mean_x50,C_mean_x100,steady_change; one row per check
// (steady_change empty while undefined).
void write_history_csv(const std::filesystem::path& file, const std::vector<HistoryRow>& rows);
// The outlet in time (output.outlet_interval > 0): at x = L, the flow-weighted mean
//   C_flow = sum_k u(y_k) C(y_k) / sum_k u(y_k)   (what leaves with the flow: the "cup-mixing"
//                                                   value a residence-time measurement reads)
// and the plain section average C_section, over the section-average points of the stations.
struct OutletRow {
  double t = 0.0;
  double c_flow = 0.0, c_section = 0.0;
};
// outlet.csv: header t_s,C_flow_mean,C_section_mean; one row per sample.
void write_outlet_csv(const std::filesystem::path& file, const std::vector<OutletRow>& rows);
// Readers throw std::runtime_error naming the file and the line on bad content.
std::vector<OutletRow> read_outlet_csv(const std::filesystem::path& file);
ProbeTable read_probes_csv(const std::filesystem::path& file);
StationTable read_stations_csv(const std::filesystem::path& file);

}  // namespace adrsph
