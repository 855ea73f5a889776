// What a study's runs directory says about each run, and the files the study keeps there:
// RUNS_DIR/<name>/ (the run), <name>.partial/checkpoint.h5 (an interrupted run),
// <name>.args.json (the run's arguments when first started), <name>.log, study.json.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "adrsph/simulation.hpp"
#include "analysis/study_plan.hpp"

namespace adrsph::cli {

struct RunFiles {
  std::filesystem::path dir, partial, checkpoint, args, log;
};
RunFiles run_files(const std::filesystem::path& runs_dir, const std::string& name);

enum class RunState {
  fresh,   // nothing usable on disk: start it
  resume,  // <name>.partial/checkpoint.h5: continue it with `run --restart`
  done,    // run.json with status "ok" or "failed", and no checkpoint
  stale,   // done or interrupted by an engine of another kResultsVersion: to be run again
};
RunState run_state(const RunFiles& f);
const char* to_string(RunState s);  // "new", "resume", "done", "stale"
// Anything of the run on disk (its directory, staging directory, arguments or log).
bool run_present(const RunFiles& f);
// Move a stale run's files to RUNS_DIR/stale/<name>.<label>[.<k>]/ (kept for comparison, out
// of the study's way), the label "v<version>" by default. Returns that directory.
std::filesystem::path retire_stale_run(const std::filesystem::path& runs_dir,
                                       const std::string& name, const std::string& label = {});

// A study continued on another machine finds its runs directory empty, but the committed
// report keeps a copy of every done run's small files (REPORT_DIR/runs/<name>/: run.json,
// probes.csv, stations.csv, history.csv, compare.csv). Copies them back into RUNS_DIR/<name>
// for each run that has nothing on disk, so that it is not computed again (its fields.h5 is
// not in the report: contour plots need a run made on this machine). Returns the names.
std::vector<std::string> restore_from_report(const std::filesystem::path& runs_dir,
                                             const std::filesystem::path& report_dir,
                                             const std::vector<analysis::StudyRun>& runs);

// The runs whose done copy in REPORT_DIR restore_from_report would take back (nothing of them
// in RUNS_DIR). A report written from RUNS_DIR now would drop them: the study writes none.
std::vector<std::string> report_only_runs(const std::filesystem::path& runs_dir,
                                          const std::filesystem::path& report_dir,
                                          const std::vector<analysis::StudyRun>& runs);

// The run.json fields the study prints. `status` is empty when there is no readable run.json.
struct RunRecord {
  std::string status, message;
  double wall_seconds = 0, t_reached = 0;
  std::optional<double> t_steady;
  int results_version = 1;  // run.json `results_version` (absent before version 2)
  // run.json `overrides`: the --set values the run was made with (none if absent).
  std::optional<std::vector<std::string>> overrides;
};
RunRecord read_run_record(const std::filesystem::path& run_dir);

// <name>.args.json: {"argv": [...], "case": "...", "sets": [...]}. The case and sets say
// what the run computes; argv (with this executable and --threads) is for the record.
struct RunArgs {
  std::string case_file;
  std::vector<std::string> sets;
  int results_version = kResultsVersion;  // of the engine that started the run (1 if absent)
};
void write_run_args(const std::filesystem::path& file, const std::vector<std::string>& argv,
                    const RunArgs& args);
std::optional<RunArgs> read_run_args(const std::filesystem::path& file);
// The --set values a run on disk was made with: <name>.args.json, or for a run without it (one
// restored from a report) its run.json `overrides`. None when neither says.
std::optional<std::vector<std::string>> recorded_sets(const RunFiles& f);

// One line of study.json's "runs".
struct StudyJsonRun {
  const analysis::StudyRun* run;
  std::string status;   // "done", "failed", "pending", "interrupted"
  std::string message;  // why it failed, when run.json does not say
};
// Writes RUNS_DIR/study.json (through a temporary file: the report may be reading it).
void write_study_json(const std::filesystem::path& runs_dir, const std::string& name,
                      const std::string& study_file, const std::vector<StudyJsonRun>& runs);

}  // namespace adrsph::cli
