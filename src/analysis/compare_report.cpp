// The compare outputs: the line errors as CSV (figures 3-5 data) and the Markdown report
// with the paper's table 3 beside ours (docs/benchmark.md, section 4).
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "analysis/compare.hpp"

namespace adrsph::analysis {
namespace {

std::string percent(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f%%", 100.0 * v);
  return buf;
}

std::string fixed(double v, const char* fmt) {
  char buf[32];
  std::snprintf(buf, sizeof buf, fmt, v);
  return buf;
}

}  // namespace

void write_line_errors_csv(const std::filesystem::path& file, const LineErrors& e) {
  std::ofstream out(file, std::ios::binary);
  if (!out) throw std::runtime_error(file.string() + ": cannot open for writing");
  out << "x_mm,err_y0,err_y+2.5,err_y-2.5,err_mean\n";
  for (std::size_t i = 0; i < e.x_mm.size(); ++i)
    out << fixed(e.x_mm[i], "%.10g") << ',' << fixed(e.err_y0[i], "%.10g") << ','
        << fixed(e.err_yp25[i], "%.10g") << ',' << fixed(e.err_ym25[i], "%.10g") << ','
        << fixed(e.err_mean[i], "%.10g") << '\n';
  if (!out) throw std::runtime_error(file.string() + ": write failed");
}

std::string compare_markdown(const std::string& run_name, const std::string& ref_name,
                             const RunInfo& info, const std::vector<StationError>& stations,
                             const std::vector<LineSummary>& lines) {
  const bool paper = info.paper_kinetics;
  const bool modern = paper && info.scheme && *info.scheme == "modern";
  const bool conventional = paper && info.scheme && *info.scheme == "conventional";
  const bool both = paper && !modern && !conventional;
  std::string md = "# " + run_name + " against " + ref_name + "\n\n";
  md += "Pe = " + (info.pe ? fixed(*info.pe, "%g") : std::string("unknown")) +
        ", scheme = " + info.scheme.value_or("unknown") + "\n\n";
  if (paper) {
    md += "## Section average, relative error (the paper's table 3)\n\n";
    md +=
        "The paper's numbers are for its fine resolution (dx = 0.125 mm); docs/benchmark.md, "
        "section 4.\n\n";
  } else {
    md += "## Section average, relative error\n\n";
    md += "The paper's table 3 is of its first-order kinetics, not of these: no paper columns.\n\n";
  }
  md += "| x [mm] | C_ref | C_run | error (ours) |";
  std::string rule = "|---|---|---|---|";
  if (modern || both) md += " paper, modern |", rule += "---|";
  if (conventional || both) md += " paper, conventional |", rule += "---|";
  md += "\n" + rule + "\n";
  for (const StationError& s : stations) {
    md += "| " + fixed(s.x_mm, "%g") + " | " + fixed(s.c_ref, "%.6f") + " | " +
          fixed(s.c_run, "%.6f") + " | " + percent(s.rel_error) + " |";
    auto paper = [](const std::optional<double>& v) {
      std::string cell(" ");  // built by appends: GCC 12 -Wrestrict misfires on " " + str
      cell += v ? percent(*v) : std::string("n/a");
      cell += " |";
      return cell;
    };
    if (modern || both) md += paper(s.paper_modern);
    if (conventional || both) md += paper(s.paper_conventional);
    md += "\n";
  }
  md += "\n## Probe lines, relative error |C - C_ref| / C_ref (the paper's figures 3-5)\n\n";
  md += "| line | max | mean |\n|---|---|---|\n";
  for (const LineSummary& l : lines)
    md += std::string("| ") + l.name + " | " + percent(l.max) + " | " + percent(l.mean) + " |\n";
  return md;
}

}  // namespace adrsph::analysis
