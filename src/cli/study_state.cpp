// Reading and writing the study's files in its runs directory.
#include "cli/study_state.hpp"

#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace adrsph::cli {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

std::optional<Json> read_json(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  Json j = Json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object()) return std::nullopt;
  return j;
}

void write_json(const fs::path& file, const Json& j) {
  fs::path tmp = file;
  tmp += ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << j.dump(2) << "\n";
    if (!out) throw std::runtime_error(tmp.string() + ": write failed");
  }
  fs::rename(tmp, file);
}

double number_or(const Json& j, const char* key, double fallback) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : fallback;
}

}  // namespace

RunFiles run_files(const fs::path& runs_dir, const std::string& name) {
  RunFiles f;
  f.dir = runs_dir / name;
  f.partial = runs_dir / (name + ".partial");
  f.checkpoint = f.partial / "checkpoint.h5";
  f.args = runs_dir / (name + ".args.json");
  f.log = runs_dir / (name + ".log");
  return f;
}

RunState run_state(const RunFiles& f) {
  std::error_code ec;
  if (fs::exists(f.checkpoint, ec)) {
    const auto args = read_run_args(f.args);
    return args && args->results_version != kResultsVersion ? RunState::stale : RunState::resume;
  }
  const RunRecord r = read_run_record(f.dir);
  if (r.status != "ok" && r.status != "failed") return RunState::fresh;
  return r.results_version == kResultsVersion ? RunState::done : RunState::stale;
}

fs::path retire_stale_run(const fs::path& runs_dir, const std::string& name,
                          const std::string& label) {
  const RunFiles f = run_files(runs_dir, name);
  int version = read_run_record(f.dir).results_version;
  if (!fs::exists(f.dir / "run.json"))
    if (const auto args = read_run_args(f.args)) version = args->results_version;
  // (Built by appends: g++ 12 sees a false -Wrestrict in the one-expression form.)
  std::string base = name;
  base += '.';
  if (label.empty()) {
    base += 'v';
    base += std::to_string(version);
  } else {
    base += label;
  }
  fs::path to = runs_dir / "stale" / base;
  for (int k = 2; fs::exists(to); ++k) to = runs_dir / "stale" / (base + "." + std::to_string(k));
  fs::create_directories(to);
  for (const fs::path& p : {f.dir, f.partial, f.args, f.log})
    if (fs::exists(p)) fs::rename(p, to / p.filename());
  return to;
}

const char* to_string(RunState s) {
  switch (s) {
    case RunState::fresh:
      return "new";
    case RunState::resume:
      return "resume";
    case RunState::done:
      return "done";
    case RunState::stale:
      return "stale";
  }
  return "?";
}

bool run_present(const RunFiles& f) {
  std::error_code ec;
  return fs::exists(f.dir, ec) || fs::exists(f.partial, ec) || fs::exists(f.args, ec) ||
         fs::exists(f.log, ec);
}

namespace {
// The report's copy of run r is one this study would take back: a run.json of this results
// version, made with the settings the study gives r now, and nothing of r in RUNS_DIR.
bool restorable(const fs::path& runs_dir, const fs::path& report_dir, const analysis::StudyRun& r) {
  const RunRecord saved = read_run_record(report_dir / "runs" / r.name);
  return !run_present(run_files(runs_dir, r.name)) && !saved.status.empty() &&
         saved.results_version == kResultsVersion &&
         (!saved.overrides || *saved.overrides == r.sets);
}
}  // namespace

std::vector<std::string> report_only_runs(const fs::path& runs_dir, const fs::path& report_dir,
                                          const std::vector<analysis::StudyRun>& runs) {
  std::vector<std::string> names;
  for (const analysis::StudyRun& r : runs)
    if (restorable(runs_dir, report_dir, r)) names.push_back(r.name);
  return names;
}

std::vector<std::string> restore_from_report(const fs::path& runs_dir, const fs::path& report_dir,
                                             const std::vector<analysis::StudyRun>& runs) {
  std::vector<std::string> restored;
  for (const analysis::StudyRun& r : runs) {
    if (!restorable(runs_dir, report_dir, r)) continue;
    const RunFiles f = run_files(runs_dir, r.name);
    const fs::path copy = report_dir / "runs" / r.name;
    std::error_code ec;
    fs::create_directories(f.dir.parent_path(), ec);
    fs::copy(copy, f.dir, fs::copy_options::recursive, ec);
    if (ec)
      throw std::runtime_error("cannot restore " + r.name + " from " + copy.string() + ": " +
                               ec.message());
    restored.push_back(r.name);
  }
  return restored;
}

RunRecord read_run_record(const fs::path& run_dir) {
  RunRecord r;
  const auto j = read_json(run_dir / "run.json");
  if (!j) return r;
  if (const auto it = j->find("status"); it != j->end() && it->is_string())
    r.status = it->get<std::string>();
  if (const auto it = j->find("message"); it != j->end() && it->is_string())
    r.message = it->get<std::string>();
  r.wall_seconds = number_or(*j, "wall_seconds", 0.0);
  r.t_reached = number_or(*j, "t_reached", 0.0);
  if (const auto it = j->find("t_steady"); it != j->end() && it->is_number())
    r.t_steady = it->get<double>();
  if (const auto it = j->find("results_version"); it != j->end() && it->is_number_integer())
    r.results_version = it->get<int>();
  if (const auto it = j->find("overrides"); it != j->end() && it->is_array()) {
    std::vector<std::string> sets;
    for (const Json& v : *it)
      if (v.is_string()) sets.push_back(v.get<std::string>());
    r.overrides = std::move(sets);
  }
  return r;
}

std::optional<std::vector<std::string>> recorded_sets(const RunFiles& f) {
  if (const auto args = read_run_args(f.args)) return args->sets;
  return read_run_record(f.dir).overrides;
}

void write_run_args(const fs::path& file, const std::vector<std::string>& argv,
                    const RunArgs& args) {
  Json j;
  j["argv"] = argv;
  j["case"] = args.case_file;
  j["sets"] = args.sets;
  j["results_version"] = args.results_version;
  write_json(file, j);
}

std::optional<RunArgs> read_run_args(const fs::path& file) {
  const auto j = read_json(file);
  if (!j) return std::nullopt;
  RunArgs a;
  try {
    a.case_file = j->at("case").get<std::string>();
    a.sets = j->at("sets").get<std::vector<std::string>>();
    a.results_version = j->value("results_version", 1);
  } catch (const Json::exception&) {
    return std::nullopt;
  }
  return a;
}

void write_study_json(const fs::path& runs_dir, const std::string& name,
                      const std::string& study_file, const std::vector<StudyJsonRun>& runs) {
  Json j;
  j["name"] = name;
  j["study_file"] = study_file;
  Json list = Json::array();
  std::map<std::string, double> references;  // Pe label -> Pe, each once
  Json refs = Json::array();
  for (const StudyJsonRun& r : runs) {
    const std::string ref_dir = "reference/pe" + r.run->pe_label;
    Json e;
    e["name"] = r.run->name;
    e["group"] = r.run->group;
    e["dir"] = r.run->name;  // relative to the runs directory, like "reference"
    e["reference"] = ref_dir;
    e["sets"] = r.run->sets;
    e["Pe"] = r.run->pe;
    e["status"] = r.status;
    if (!r.message.empty()) e["message"] = r.message;
    list.push_back(e);
    if (references.emplace(r.run->pe_label, r.run->pe).second)
      refs.push_back(Json{{"Pe", r.run->pe}, {"dir", ref_dir}});
  }
  j["runs"] = list;
  j["references"] = refs;
  write_json(runs_dir / "study.json", j);
}

}  // namespace adrsph::cli
