// The plan of an `adrsph study`: the study file (TOML) read and checked, and its matrix of
// runs expanded into names and --set overrides. Pure: no process is started and nothing is
// written; only the study file and the base case file are read.
// The study-file format is documented in cases/README.md ("Study files").
#pragma once

#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "adrsph/case.hpp"

namespace adrsph::analysis {

// A bad study file. `what()` names the study file, where in it (a group, a run), the key
// and what was expected, in the style of CaseError:
// "FILE: group 'paper': key 'dx': expected a number > 0 or a list of them, got string \"a\"".
class StudyError : public std::runtime_error {
 public:
  StudyError(const std::string& file, const std::string& where, const std::string& key,
             const std::string& expected);
  const std::string& key() const { return key_; }

 private:
  std::string key_;
};

// One key of a group: a fixed value (scalar) or an axis (a list in the file). Values are
// kept as TOML text ("0.5", "true", "\"modern\"") plus the form used in run names.
struct StudyValue {
  std::string toml;   // as --set takes it
  std::string label;  // the run-name part: "modern", "pe1000", "dx0.125", "aletrue"
  double number = 0;  // for Pe and dx
};

struct StudyKey {
  std::string key;                 // "scheme", "flow", "Pe", "dx" or a dotted case key
  std::vector<StudyValue> values;  // one value when fixed
  bool axis = false;               // a list in the file: one run per value
};

struct StudyGroup {
  std::string name;
  // `set` (fixed overrides, "key=value") and the group's keys, each in file order; `set`
  // comes first.
  std::vector<std::string> set;
  std::vector<StudyKey> keys;
  bool force = false;  // `force = true`: runs get --force (settings known unstable: stress maps)
};

struct StudyFile {
  std::filesystem::path file;       // the study file, as given
  std::string name;                 // `name` (default: the file name without .toml)
  std::filesystem::path case_file;  // `case`, resolved against the study file's directory
  std::optional<std::filesystem::path> runs_dir, report_dir;  // resolved likewise
  std::optional<int> threads;
  int reference_nx = 1600, reference_ny = 160;  // [reference]
  // `report`: "study" (tools/study_report.py, the paper's tables and plots) or "stress"
  // (tools/stress_report.py, the stability map).
  std::string report = "study";
  std::vector<StudyGroup> groups;
};

// One run of the matrix, fully resolved.
struct StudyRun {
  std::string name;  // e.g. "paper-conventional-pe1000-dx0.125"
  std::string group;
  std::vector<std::string> sets;  // the --set overrides, "key=value", in file order
  double pe = 0;                  // Peclet number of the run's case
  double D = 0;                   // its species.D
  std::string pe_label;           // "1000": names the reference directory reference/pe<label>
  bool force = false;             // its group's `force`: adrsph run --force
};

// Reads and checks the study file (keys, types, names). Throws StudyError.
StudyFile parse_study(const std::filesystem::path& file);
// Same from text; `file` names it in errors and resolves relative paths.
StudyFile parse_study_text(const std::string& text, const std::filesystem::path& file);

// The runs of the study in order: groups in file order, each group's axes as nested loops in
// file order, the last axis fastest. Each run's case (base case + its sets) is loaded with
// `load_case`, so a bad key or value fails here, naming the run; Pe becomes
// species.D = u_bulk * length / Pe of that case. Runs sharing a Pe must share the physics of
// the reference (D, k, c_in, u_bulk, geometry). Throws StudyError.
std::vector<StudyRun> expand_study(const StudyFile& study);

// Glob patterns (fnmatch) from --only; each argument may hold several, comma-separated.
std::vector<std::string> split_patterns(const std::vector<std::string>& args);
// Whether the run is selected: no patterns selects everything.
bool run_selected(const std::string& name, const std::vector<std::string>& patterns);

// Shortest text that reads back as the same double ("0.1", not "0.10000000000000001").
std::string format_exact(double v);
// "%.10g" for a Peclet number (100000 -> "100000"); names references and runs.
std::string format_pe(double pe);

}  // namespace adrsph::analysis
