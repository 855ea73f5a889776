// Carrying out a study's plan: the references, the SPH runs (N at once, each a child
// `adrsph run`), a `compare` after each run, and study.json kept up to date.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "analysis/study_plan.hpp"

namespace adrsph::cli {

struct StudySetup {
  const analysis::StudyFile* study = nullptr;
  const std::vector<analysis::StudyRun>* runs = nullptr;  // every run of the study
  std::vector<bool> selected;                             // by --only
  std::string study_file;      // as given on the command line (messages, study.json)
  std::string resume_command;  // what to type to continue after an interruption
  std::filesystem::path runs_dir, case_file, exe;  // absolute
  int jobs = 1, threads_per_run = 1;
};

// Runs what the selected runs still need. Returns the study's exit code: 0 all done and ok,
// 3 a run failed (numerically or otherwise), 2 a child reported bad input, 4 interrupted
// (SIGINT/SIGTERM, or a run that exited 4), 1 a reference could not be computed.
int run_study(const StudySetup& s);

}  // namespace adrsph::cli
