// `adrsph compare RUN_DIR REF_DIR [--out FILE]`: the paper's metrics (docs/benchmark.md,
// section 4; issue 4). Relative error along the three probe lines (CSV + PNG, figures 3-5) and of
// the section averages at x = 25, 50, 100 beside the paper's table 3 (Markdown, also printed).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include "adrsph/probes.hpp"

#include "analysis/compare.hpp"
#include "analysis/outlet_compare.hpp"
#include "cli/commands.hpp"
#include "cli/python_tools.hpp"

namespace adrsph::cli {
namespace {

namespace fs = std::filesystem;

struct CompareOptions {
  std::string run_dir, ref_dir, out;
  bool plot = true;
};

void plot_errors(const fs::path& csv, const fs::path& png, const std::string& title) {
  run_plot_script("plot_errors.py", {csv.string(), "--out", png.string(), "--title", title});
}

// The files of one species: probes.csv and stations.csv for the first, probes_<name>.csv and
// stations_<name>.csv for the others of a network ("" names the first).
struct SpeciesFiles {
  std::string name;
  std::string probes() const { return name.empty() ? "probes.csv" : "probes_" + name + ".csv"; }
  std::string stations() const {
    return name.empty() ? "stations.csv" : "stations_" + name + ".csv";
  }
};

// The other species of a network run: RUN_DIR/probes_<name>.csv, sorted by name.
std::vector<SpeciesFiles> more_species_of(const fs::path& run_dir) {
  std::vector<SpeciesFiles> out;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(run_dir, ec)) {
    const std::string f = e.path().filename().string();
    if (f.size() > 11 && f.rfind("probes_", 0) == 0 && f.substr(f.size() - 4) == ".csv")
      out.push_back({f.substr(7, f.size() - 11)});
  }
  std::sort(out.begin(), out.end(),
            [](const SpeciesFiles& a, const SpeciesFiles& b) { return a.name < b.name; });
  return out;
}

// One species of the run against the same species of the reference; writes md_file and its
// .csv and .png beside it.
int compare_species(const CompareOptions& o, const SpeciesFiles& sp, analysis::RunInfo info,
                    const fs::path& md_file) {
  const fs::path run_dir = o.run_dir, ref_dir = o.ref_dir;
  ProbeTable run_probes, ref_probes;
  StationTable run_stations, ref_stations;
  try {
    run_probes = read_probes_csv(run_dir / sp.probes());
    run_stations = read_stations_csv(run_dir / sp.stations());
    ref_probes = read_probes_csv(ref_dir / sp.probes());
    ref_stations = read_stations_csv(ref_dir / sp.stations());
  } catch (const std::exception& e) {
    std::cerr << "adrsph compare: " << e.what()
              << (sp.name.empty() ? "" : " (species " + sp.name + " of the run)") << "\n";
    return kExitBadInput;
  }
  analysis::LineErrors lines;
  std::vector<analysis::StationError> stations;
  try {
    lines = analysis::line_errors(run_probes, ref_probes);
    stations = analysis::station_errors(run_stations, ref_stations,
                                        info.paper_kinetics ? info.pe : std::nullopt);
  } catch (const std::exception& e) {
    std::cerr << "adrsph compare: " << e.what() << "\n";
    return kExitBadInput;
  }
  std::string run_name =
      run_dir.filename().empty() ? run_dir.string() : run_dir.filename().string();
  if (!sp.name.empty()) run_name += " (species " + sp.name + ")";
  const std::string md = analysis::compare_markdown(run_name, ref_dir.string(), info, stations,
                                                    analysis::summarise(lines));
  std::cout << md;

  fs::path csv_file = md_file, png_file = md_file;
  csv_file.replace_extension(".csv");
  png_file.replace_extension(".png");
  try {
    if (md_file.has_parent_path()) fs::create_directories(md_file.parent_path());
    std::ofstream out(md_file, std::ios::binary);
    out << md;
    if (!out) throw std::runtime_error(md_file.string() + ": write failed");
    analysis::write_line_errors_csv(csv_file, lines);
  } catch (const std::exception& e) {
    std::cerr << "adrsph compare: " << e.what() << "\n";
    return kExitIoError;
  }
  std::printf("\nwrote %s and %s\n", md_file.c_str(), csv_file.c_str());
  if (o.plot)
    plot_errors(csv_file, png_file, "relative error: " + run_name + " against " + o.ref_dir);
  return kExitOk;
}

// The species names of RUN_DIR/run.json ("species": [{"name": ...}, ...] of a run, or
// ["A", ...] of a transient reference); one unnamed species when it lists none.
std::vector<std::string> species_names_of(const fs::path& run_json) {
  std::vector<std::string> names;
  std::ifstream in(run_json, std::ios::binary);
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (!j.is_discarded() && j.contains("species") && j["species"].is_array()) {
    for (const auto& s : j["species"]) {
      if (s.is_object() && s.contains("name") && s["name"].is_string())
        names.push_back(s["name"].get<std::string>());
      else if (s.is_string())
        names.push_back(s.get<std::string>());
    }
  }
  if (names.empty()) names.push_back("");
  return names;
}

// Against a transient reference (REF_DIR/outlet.csv and no stations.csv): every species'
// outlet series, outlet.csv for the first, outlet_<name>.csv for the others.
int compare_outlets(const CompareOptions& o) {
  const fs::path run_dir = o.run_dir, ref_dir = o.ref_dir;
  const std::vector<std::string> names = species_names_of(run_dir / "run.json");
  std::vector<analysis::OutletSeriesError> rows;
  for (std::size_t s = 0; s < names.size(); ++s) {
    const std::string file = s == 0 ? std::string("outlet.csv") : "outlet_" + names[s] + ".csv";
    try {
      rows.push_back(analysis::outlet_series_error(names[s], read_outlet_csv(run_dir / file),
                                                   read_outlet_csv(ref_dir / file)));
    } catch (const std::invalid_argument& e) {
      std::cerr << "adrsph compare: " << file << ": " << e.what() << "\n";
      return kExitBadInput;
    } catch (const std::exception& e) {  // the reader names the file and the line
      std::cerr << "adrsph compare: " << e.what() << "\n";
      return kExitBadInput;
    }
  }
  const std::string run_name =
      run_dir.filename().empty() ? run_dir.string() : run_dir.filename().string();
  const std::string md = analysis::outlet_compare_markdown(run_name, ref_dir.string(), rows);
  std::cout << md;
  const fs::path md_file = o.out.empty() ? run_dir / "compare_outlet.md" : fs::path(o.out);
  try {
    if (md_file.has_parent_path()) fs::create_directories(md_file.parent_path());
    std::ofstream out(md_file, std::ios::binary);
    out << md;
    if (!out) throw std::runtime_error(md_file.string() + ": write failed");
  } catch (const std::exception& e) {
    std::cerr << "adrsph compare: " << e.what() << "\n";
    return kExitIoError;
  }
  std::printf("\nwrote %s\n", md_file.c_str());
  return kExitOk;
}

int run_compare(const CompareOptions& o) {
  const fs::path run_dir = o.run_dir, ref_dir = o.ref_dir;
  std::error_code ec;
  if (fs::exists(ref_dir / "outlet.csv", ec) && !fs::exists(ref_dir / "stations.csv", ec))
    return compare_outlets(o);
  analysis::RunInfo info = analysis::read_run_info(run_dir / "run.json");
  if (!info.pe) info.pe = analysis::read_run_info(ref_dir / "reference.json").pe;
  const std::vector<SpeciesFiles> more = more_species_of(run_dir);
  // The paper's table 3 is of one species with first-order kinetics: not for a network.
  if (!more.empty()) info.paper_kinetics = false;
  const fs::path md_file = o.out.empty() ? run_dir / "compare.md" : fs::path(o.out);
  if (const int rc = compare_species(o, {}, info, md_file); rc != kExitOk) return rc;
  for (const SpeciesFiles& sp : more) {
    fs::path file = md_file;
    file.replace_filename(md_file.stem().string() + "_" + sp.name + md_file.extension().string());
    std::cout << "\n";
    if (const int rc = compare_species(o, sp, info, file); rc != kExitOk) return rc;
  }
  return kExitOk;
}

}  // namespace

Command register_compare(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "compare",
      "Relative error of a run against a reference (docs/benchmark.md, section 4): along the "
      "probe lines "
      "y = 0, +2.5, -2.5 and of the section average (the paper's figures 3-5), and of the "
      "section averages at x = 25, 50, 100 beside the paper's table 3 (row chosen by Pe and "
      "scheme from RUN_DIR/run.json). Reads probes.csv and stations.csv of both, and for a "
      "network run each species' probes_<name>.csv and stations_<name>.csv (written beside "
      "FILE as FILE_<name>.md, .csv, .png). Writes FILE "
      "(Markdown, default RUN_DIR/compare.md), FILE with .csv (x_mm,err_y0,err_y+2.5,"
      "err_y-2.5,err_mean) and FILE with .png (tools/plot_errors.py, when a python3 with "
      "matplotlib is found; $ADRSPH_PYTHON overrides).\n"
      "Against a transient reference (`adrsph reference CASE --transient`: REF_DIR holds "
      "outlet.csv and no stations.csv), the outlet series of every species instead (outlet.csv, "
      "outlet_<name>.csv): the excursion from t = 0, its integral, peak, L1 and largest "
      "distance; FILE defaults to RUN_DIR/compare_outlet.md.\n"
      "Exit codes: 0 ok, 1 I/O error, 2 bad input (missing or malformed CSV).");
  auto o = std::make_shared<CompareOptions>();
  sub->add_option("run_dir", o->run_dir, "Run directory (adrsph run --out)")->required();
  sub->add_option("ref_dir", o->ref_dir, "Reference directory (adrsph reference --out)")
      ->required();
  sub->add_option("--out", o->out, "Markdown report (default RUN_DIR/compare.md)")
      ->check(kNonEmptyPath);
  sub->add_flag("!--no-plot", o->plot, "Do not draw the PNG");
  return {sub, [o] { return run_compare(*o); }};
}

}  // namespace adrsph::cli
