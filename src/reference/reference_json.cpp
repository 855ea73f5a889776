// DIR/reference.json: what was solved and how (issue 4). Written by hand: flat keys plus
// the station averages, numbers at full precision.
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "adrsph/reference.hpp"

namespace adrsph::reference {
namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::string quoted(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) {
    if (ch == '"' || ch == '\\') {
      out += '\\';
      out += ch;
    } else if (static_cast<unsigned char>(ch) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", ch);
      out += buf;
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

}  // namespace

void write_reference_json(const std::filesystem::path& file, const std::string& case_name,
                          const Solution& s, const Problem& p) {
  const SolveReport& r = s.report;
  const StationTable st = station_table(s, p);
  std::string j = "{\n";
  auto field = [&j](const char* key, const std::string& value) {
    j += "  " + quoted(key) + ": " + value + ",\n";
  };
  field("case", quoted(case_name));
  field("nx", std::to_string(s.grid.nx));
  field("ny", std::to_string(s.grid.ny));
  field("length", number(p.length));
  field("half_width", number(p.half_width));
  field("D", number(p.D));
  field("k", number(p.k));
  // The [[reaction]] tables: their laws (the case file has the rest).
  std::string laws = "[";
  for (const Reaction& rx : p.reactions)
    laws.append(laws.size() > 1 ? ", " : "").append(quoted(to_string(rx.law)));
  field("reactions", laws + "]");
  field("c_in", number(p.c_in));
  field("u_bulk", number(p.u_bulk));
  field("Pe", number(p.peclet()));
  field("solver", quoted(r.solver));
  field("assembly_seconds", number(r.assembly_seconds));
  field("solve_seconds", number(r.solve_seconds));
  field("corrections", std::to_string(r.corrections));
  field("last_change", number(r.last_change));
  field("residual", number(r.residual));
  field("converged", r.converged ? "true" : "false");
  j += "  \"stations\": [";
  for (std::size_t m = 0; m < st.x_mm.size(); ++m)
    j += std::string(m ? ", " : "") + "{\"x_mm\": " + number(st.x_mm[m]) +
         ", \"C_mean\": " + number(st.c_mean[m]) + "}";
  j += "]\n}\n";

  std::ofstream out(file, std::ios::binary);
  if (!out) throw std::runtime_error(file.string() + ": cannot open for writing");
  out << j;
  if (!out) throw std::runtime_error(file.string() + ": write failed");
}

}  // namespace adrsph::reference
