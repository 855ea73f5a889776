// probes.csv / stations.csv: the probe contract shared by `run`, `reference` and `compare`
// (include/adrsph/probes.hpp; docs/benchmark.md, section 4). Full precision (%.10g), exact headers.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "adrsph/probes.hpp"

namespace adrsph {
namespace {

constexpr const char* kProbesHeader = "x_mm,C_y0,C_y+2.5,C_y-2.5,C_mean";
constexpr const char* kStationsHeader = "x_mm,C_mean";
constexpr const char* kOutletHeader = "t_s,C_flow_mean,C_section_mean";

[[noreturn]] void fail(const std::filesystem::path& file, long line, const std::string& what) {
  throw std::runtime_error(file.string() + ":" + std::to_string(line) + ": " + what);
}

std::string format_row(const double* values, std::size_t n) {
  std::string row;
  char buf[32];
  for (std::size_t k = 0; k < n; ++k) {
    std::snprintf(buf, sizeof buf, "%.10g", values[k]);
    if (k) row += ',';
    row += buf;
  }
  return row;
}

void write_text(const std::filesystem::path& file, const std::string& text) {
  std::ofstream out(file, std::ios::binary);
  if (!out) throw std::runtime_error(file.string() + ": cannot open for writing");
  out << text;
  if (!out) throw std::runtime_error(file.string() + ": write failed");
}

// Reads a CSV whose first line must be `header` and whose rows hold exactly `ncols`
// finite numbers; calls `row(values)` for each data row. Blank lines are skipped.
template <class RowFn>
void read_table(const std::filesystem::path& file, const char* header, std::size_t ncols,
                RowFn&& row) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw std::runtime_error(file.string() + ": cannot open for reading");
  std::string line;
  long lineno = 0;
  bool header_seen = false;
  std::vector<double> values;
  while (std::getline(in, line)) {
    ++lineno;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    if (!header_seen) {
      if (line != header)
        fail(file, lineno, "expected header '" + std::string(header) + "', got '" + line + "'");
      header_seen = true;
      continue;
    }
    values.clear();
    std::stringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ',')) {
      std::size_t used = 0;
      double v = 0.0;
      try {
        v = std::stod(field, &used);
      } catch (const std::exception&) {
        fail(file, lineno, "not a number: '" + field + "'");
      }
      if (field.find_first_not_of(" \t", used) != std::string::npos)
        fail(file, lineno, "not a number: '" + field + "'");
      if (!std::isfinite(v)) fail(file, lineno, "non-finite value: '" + field + "'");
      values.push_back(v);
    }
    if (!line.empty() && line.back() == ',') values.push_back(NAN);  // trailing empty field
    if (values.size() != ncols)
      fail(file, lineno,
           "expected " + std::to_string(ncols) + " fields, got " + std::to_string(values.size()));
    row(values);
  }
  if (!header_seen) fail(file, lineno, "empty file, expected header '" + std::string(header) + "'");
}

}  // namespace

std::vector<double> probe_x_positions(double length) {
  std::vector<double> x;
  const long n = std::lround(std::floor(length / 0.5 + 1e-9));
  for (long i = 1; i <= n; ++i) x.push_back(0.5 * static_cast<double>(i));
  return x;
}

std::vector<double> station_x_positions(double length) {
  const double s = length / 100.0;
  return {25.0 * s, 50.0 * s, 100.0 * s};
}

void write_probes_csv(const std::filesystem::path& file, const ProbeTable& t) {
  const std::size_t n = t.x_mm.size();
  if (t.c_y0.size() != n || t.c_yp25.size() != n || t.c_ym25.size() != n || t.c_mean.size() != n)
    throw std::runtime_error(file.string() + ": probe table columns differ in length");
  std::string text = std::string(kProbesHeader) + "\n";
  for (std::size_t i = 0; i < n; ++i) {
    const double row[] = {t.x_mm[i], t.c_y0[i], t.c_yp25[i], t.c_ym25[i], t.c_mean[i]};
    text += format_row(row, 5) + "\n";
  }
  write_text(file, text);
}

void write_stations_csv(const std::filesystem::path& file, const StationTable& t) {
  if (t.c_mean.size() != t.x_mm.size())
    throw std::runtime_error(file.string() + ": station table columns differ in length");
  std::string text = std::string(kStationsHeader) + "\n";
  for (std::size_t i = 0; i < t.x_mm.size(); ++i) {
    const double row[] = {t.x_mm[i], t.c_mean[i]};
    text += format_row(row, 2) + "\n";
  }
  write_text(file, text);
}

void write_history_csv(const std::filesystem::path& file, const std::vector<HistoryRow>& rows) {
  std::string text = "t_s,C_mean_x25,C_mean_x50,C_mean_x100,steady_change\n";
  for (const HistoryRow& r : rows) {
    if (r.stations.size() != 3)
      throw std::runtime_error(file.string() + ": a history row needs 3 station values");
    const double row[] = {r.t, r.stations[0], r.stations[1], r.stations[2]};
    text += format_row(row, 4) + ",";
    if (std::isfinite(r.steady_change)) {
      const double ch[] = {r.steady_change};
      text += format_row(ch, 1);
    }
    text += "\n";
  }
  write_text(file, text);
}

void write_outlet_csv(const std::filesystem::path& file, const std::vector<OutletRow>& rows) {
  std::string text = std::string(kOutletHeader) + "\n";
  for (const OutletRow& r : rows) {
    const double row[] = {r.t, r.c_flow, r.c_section};
    text += format_row(row, 3) + "\n";
  }
  write_text(file, text);
}

std::vector<OutletRow> read_outlet_csv(const std::filesystem::path& file) {
  std::vector<OutletRow> rows;
  read_table(file, kOutletHeader, 3, [&](const std::vector<double>& v) {
    if (!rows.empty() && !(v[0] > rows.back().t))
      throw std::runtime_error(file.string() + ": times must increase, got " +
                               std::to_string(v[0]) + " after " + std::to_string(rows.back().t));
    rows.push_back({v[0], v[1], v[2]});
  });
  return rows;
}

ProbeTable read_probes_csv(const std::filesystem::path& file) {
  ProbeTable t;
  read_table(file, kProbesHeader, 5, [&](const std::vector<double>& v) {
    t.x_mm.push_back(v[0]);
    t.c_y0.push_back(v[1]);
    t.c_yp25.push_back(v[2]);
    t.c_ym25.push_back(v[3]);
    t.c_mean.push_back(v[4]);
  });
  return t;
}

StationTable read_stations_csv(const std::filesystem::path& file) {
  StationTable t;
  read_table(file, kStationsHeader, 2, [&](const std::vector<double>& v) {
    t.x_mm.push_back(v[0]);
    t.c_mean.push_back(v[1]);
  });
  return t;
}

}  // namespace adrsph
