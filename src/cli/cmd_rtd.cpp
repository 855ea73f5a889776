// `adrsph rtd RUN_DIR [--species NAME] [--out DIR] [--against REF_DIR]`: the residence-time
// distribution of a tracer-pulse run (docs/rtd.md). Reads the run's case (case.toml with
// run.json's overrides) and its outlet in time (outlet.csv, or outlet_<NAME>.csv for a species
// of a network other than the first); writes rtd.csv, rtd.json, rtd.md and rtd.png (rtd_<NAME>.*),
// and prints rtd.md. With --against, also the transient reference's outlet (REF_DIR/outlet.csv).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "adrsph/case.hpp"
#include "adrsph/probes.hpp"
#include "analysis/rtd.hpp"
#include "analysis/rtd_against.hpp"
#include "analysis/rtd_report.hpp"
#include "cli/commands.hpp"
#include "cli/python_tools.hpp"
#include "cli/study_state.hpp"

namespace adrsph::cli {
namespace {

namespace fs = std::filesystem;

struct RtdOptions {
  std::string run_dir, out, against, species;
  bool plot = true;
};

int bad_input(const std::string& message) {
  std::cerr << "adrsph rtd: " << message << "\n";
  return kExitBadInput;
}

// Writes every file through FILE.tmp and renames them only once all are written, so that a
// failure leaves the previous outputs (or none), never a mix or a truncated file.
void write_all(const std::vector<std::pair<fs::path, std::string>>& files) {
  std::vector<fs::path> written;
  try {
    for (const auto& [file, text] : files) {
      fs::path tmp = file;
      tmp += ".tmp";
      written.push_back(tmp);
      std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
      out << text;
      out.close();
      if (!out) throw std::runtime_error(tmp.string() + ": write failed");
    }
    for (const auto& [file, text] : files) {
      fs::path tmp = file;
      tmp += ".tmp";
      fs::rename(tmp, file);
    }
  } catch (...) {
    std::error_code ec;
    for (const fs::path& tmp : written) fs::remove(tmp, ec);
    throw;
  }
}

// The case as the RTD of species s sees it: that species alone, as the case's `species`, with
// the reactions it takes part in (so that a reacting tracer is still warned of). Only the
// first species has a species.k (the one-species form's reaction); another species' kinetics
// are all in those reactions, so its k is 0 (its Species holds the unused default).
Case species_view(const Case& c, int s) {
  if (c.species_count() == 1) return c;
  Case v = c;
  v.species = c.species_at(s);
  if (s != 0) v.species.k = 0.0;
  v.more_species.clear();
  v.reactions.clear();
  for (const Reaction& r : c.reactions) {
    const auto takes_part = [s](const std::vector<int>& ids) {
      return std::find(ids.begin(), ids.end(), s) != ids.end();
    };
    if (takes_part(r.reactants) || takes_part(r.products)) v.reactions.push_back(r);
  }
  v.name = c.name + " (species " + c.species_at(s).name + ")";
  return v;
}

// Index of the species --species names (the first when it is empty), or nullopt.
std::optional<int> species_index(const Case& c, const std::string& name) {
  if (name.empty()) return 0;
  for (int s = 0; s < c.species_count(); ++s)
    if (c.species_at(s).name == name) return s;
  return std::nullopt;
}

std::string species_names(const Case& c) {
  std::string names;
  for (int s = 0; s < c.species_count(); ++s)
    names += (s ? ", \"" : "\"") + c.species_at(s).name + "\"";
  return names;
}

void plot_rtd(const fs::path& csv, const fs::path& json, const fs::path& png,
              const std::string& title) {
  run_plot_script("plot_rtd.py",
                  {csv.string(), "--json", json.string(), "--out", png.string(), "--title", title});
}

// The transient reference of --against (docs/rtd.md, "Against the transient reference"):
// REF_DIR/outlet<suffix>.csv, and the case it was solved for, REF_DIR/case.toml with
// REF_DIR/run.json's overrides (the run's case when REF_DIR holds no case.toml), seen as the
// run's species `species` (species_view). On bad input, nothing and `error` says what, naming
// the file.
std::optional<analysis::RtdAgainst> compare_with_reference(const fs::path& ref_dir,
                                                           const analysis::Rtd& r,
                                                           const Case& run_case, int species,
                                                           const std::string& suffix,
                                                           std::string& error) {
  const fs::path outlet_csv = ref_dir / ("outlet" + suffix + ".csv"),
                 case_file = ref_dir / "case.toml";
  std::error_code ec;
  if (!fs::exists(outlet_csv, ec)) {
    error = outlet_csv.string() +
            ": not found; --against needs the output directory of `adrsph reference CASE "
            "--transient` (its outlet series)";
    return std::nullopt;
  }
  Case ref_case = run_case;  // the whole case, a network's every species
  if (fs::exists(case_file, ec)) {
    const fs::path run_json = ref_dir / "run.json";
    std::vector<std::string> overrides;
    if (fs::exists(run_json, ec)) {
      std::ifstream in(run_json, std::ios::binary);
      if (!nlohmann::json::accept(in)) {
        error = run_json.string() +
                ": not valid JSON (its \"overrides\" are the --set values "
                "the reference was solved with)";
        return std::nullopt;
      }
      overrides = read_run_record(ref_dir).overrides.value_or(std::vector<std::string>{});
    }
    try {
      ref_case = load_case(case_file, overrides);
    } catch (const CaseError& e) {
      error =
          (e.file() == "--set" ? run_json.string() + ": overrides: " : std::string()) + e.what();
      return std::nullopt;
    }
  }
  const std::string name = run_case.species_at(species).name;
  const std::optional<int> rs = species_index(ref_case, run_case.species_count() > 1 ? name : "");
  if (!rs || *rs != species || ref_case.species_count() != run_case.species_count()) {
    error = case_file.string() + ": the reference was solved for species " +
            species_names(ref_case) + ", the run has " + species_names(run_case);
    return std::nullopt;
  }
  try {
    return analysis::against_reference(r, species_view(run_case, species),
                                       read_outlet_csv(outlet_csv), species_view(ref_case, *rs));
  } catch (const analysis::RtdInputError& e) {
    error = outlet_csv.string() + ": " + e.what();
  } catch (const std::exception& e) {  // read_outlet_csv names the file and the line
    error = e.what();
  }
  return std::nullopt;
}

int run_rtd(const RtdOptions& o) {
  const fs::path run_dir = o.run_dir;
  std::error_code ec;
  if (!fs::is_directory(run_dir, ec))
    return bad_input(run_dir.string() +
                     ": no such directory; give the output directory of `adrsph run` (it holds "
                     "case.toml, run.json and outlet.csv)");
  const fs::path run_json = run_dir / "run.json", case_file = run_dir / "case.toml";
  if (!fs::exists(run_json, ec))
    return bad_input(run_json.string() +
                     ": not found; RUN_DIR must be the output directory of a finished `adrsph "
                     "run` (run.json holds the --set values the case was run with)");
  {
    // read_run_record() takes an unreadable run.json for one without overrides: refuse it
    // rather than analyse the case as it was not run.
    std::ifstream in(run_json, std::ios::binary);
    if (!nlohmann::json::accept(in))
      return bad_input(run_json.string() +
                       ": not valid JSON; it must be the run.json that `adrsph run` wrote (its "
                       "\"overrides\" are the --set values of the run)");
  }
  const std::vector<std::string> overrides =
      read_run_record(run_dir).overrides.value_or(std::vector<std::string>{});

  if (!fs::exists(case_file, ec))
    return bad_input(case_file.string() +
                     ": not found; RUN_DIR must be the output directory of `adrsph run` (it "
                     "keeps the case file as case.toml)");
  Case run_case;
  try {
    run_case = load_case(case_file, overrides);
  } catch (const CaseError& e) {
    // An override names "--set": it came from run.json.
    if (e.file() == "--set") return bad_input(run_json.string() + ": overrides: " + e.what());
    return bad_input(e.what());
  }
  const std::string case_name =
      overrides.empty() ? case_file.string() : case_file.string() + " (with run.json's --set)";
  const std::optional<int> s = species_index(run_case, o.species);
  if (!s)
    return bad_input("--species " + o.species + ": " + case_name +
                     " has no species of that name (it has " + species_names(run_case) + ")");
  // The first species keeps the file names of a one-species run; another gets _<name>.
  const std::string suffix = *s == 0 ? std::string() : "_" + run_case.species_at(*s).name;
  const Case c = species_view(run_case, *s);
  const fs::path outlet_csv = run_dir / ("outlet" + suffix + ".csv");
  try {
    analysis::check_rtd_feed(c);
  } catch (const analysis::RtdInputError& e) {
    std::string hint;
    if (run_case.species_count() > 1)
      hint = " (the RTD of species \"" + run_case.species_at(*s).name +
             "\"; --species NAME takes another of " + species_names(run_case) + ")";
    return bad_input(case_name + ": " + e.what() + hint);
  }
  if (!fs::exists(outlet_csv, ec))
    return bad_input(outlet_csv.string() +
                     ": not found; the run must set output.outlet_interval > 0 (the outlet "
                     "sampling interval in s, e.g. --set output.outlet_interval=0.01); run it "
                     "again with it");

  analysis::Rtd r;
  try {
    r = analysis::residence_time_distribution(read_outlet_csv(outlet_csv), c);
  } catch (const analysis::RtdInputError& e) {
    const bool feed = e.source() == analysis::RtdInputError::Source::feed;
    return bad_input((feed ? case_name : outlet_csv.string()) + ": " + e.what());
  } catch (const std::exception& e) {  // read_outlet_csv names the file and the line
    return bad_input(e.what());
  }

  std::optional<analysis::RtdAgainst> against;
  if (!o.against.empty()) {
    std::string error;
    against = compare_with_reference(o.against, r, run_case, *s, suffix, error);
    if (!against) return bad_input(error);
  }
  const analysis::RtdAgainst* a = against ? &*against : nullptr;

  const std::string md = analysis::rtd_markdown(r, c, a);
  std::cout << md;
  const fs::path out = o.out.empty() ? run_dir : fs::path(o.out);
  const fs::path csv = out / ("rtd" + suffix + ".csv"), json = out / ("rtd" + suffix + ".json"),
                 md_file = out / ("rtd" + suffix + ".md");
  try {
    fs::create_directories(out);
    write_all({{csv, analysis::rtd_csv(r, a)}, {json, analysis::rtd_json(r, c, a)}, {md_file, md}});
  } catch (const std::exception& e) {
    std::cerr << "adrsph rtd: " << e.what() << "\n";
    return kExitIoError;
  }
  std::printf("\nwrote %s, %s and %s\n", md_file.c_str(), json.c_str(), csv.c_str());
  if (o.plot)
    plot_rtd(csv, json, out / ("rtd" + suffix + ".png"), "residence-time distribution: " + c.name);
  return kExitOk;
}

}  // namespace

Command register_rtd(CLI::App& app) {
  auto* sub = app.add_subcommand(
      "rtd",
      "Residence-time distribution of a tracer-pulse run (docs/rtd.md): the mean residence "
      "time and variance of the channel from the moments of the outlet response, corrected "
      "for the feed's, against the space time V/Q and the Taylor-Aris dispersion model.\n"
      "Needs a run made with species.feed.shape = \"pulse\" or \"table\" (a tracer input; "
      "species.k = 0 for a conserved tracer) and output.outlet_interval > 0, long enough "
      "(time.t_end) for the outlet to return to species.feed.base. Reads RUN_DIR/case.toml "
      "with the --set values of RUN_DIR/run.json, and RUN_DIR/outlet.csv. Writes rtd.csv "
      "(t_s,C_out,E_per_s,C_model,C_model_closed,C_reference), rtd.json (every figure), rtd.md "
      "(printed) and rtd.png "
      "(tools/plot_rtd.py, when a python3 with matplotlib is found; $ADRSPH_PYTHON "
      "overrides) into DIR, default RUN_DIR.\n"
      "Exit codes: 0 ok, 1 I/O error, 2 bad input (missing run directory, case.toml, run.json "
      "or outlet.csv, a feed that is not a pulse or a table, fewer than 3 samples, no tracer "
      "at the outlet; with --against, no REF_DIR/outlet.csv or one that does not cover the "
      "run's times).");
  auto o = std::make_shared<RtdOptions>();
  sub->add_option("run_dir", o->run_dir, "Run directory (adrsph run --out)")->required();
  sub->add_option("--out", o->out, "Output directory (default RUN_DIR)")->check(kNonEmptyPath);
  sub->add_option("--species", o->species,
                  "The species of a network ([[species]] tables) whose RTD to take, by name "
                  "(default the first): its feed, D and reactions, its outlet series "
                  "outlet_<NAME>.csv (outlet.csv for the first), and the outputs rtd_<NAME>.* "
                  "(rtd.* for the first)");
  sub->add_option("--against", o->against,
                  "Compare with the transient finite-volume reference of the case: the output "
                  "directory of `adrsph reference CASE --transient` (its outlet.csv must cover "
                  "the run's sample times). Adds the reference's mean residence time, variance "
                  "and the L1 distance of the normalised responses to rtd.md and rtd.json, and "
                  "the column C_reference to rtd.csv (docs/rtd.md)")
      ->check(kNonEmptyPath);
  sub->add_flag("!--no-plot", o->plot, "Do not draw the PNG");
  return {sub, [o] { return run_rtd(*o); }};
}

}  // namespace adrsph::cli
