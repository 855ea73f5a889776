// `adrsph study STUDY.toml [--only PATTERN] [--resume] [--jobs N] [--threads N] [--out DIR]
// [--report DIR] [--dry-run]`: a matrix of runs from one study file, their references and
// compares, and the report. The study-file format: cases/README.md ("Study files").
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string_view>
#include <thread>

#include "analysis/study_plan.hpp"
#include "cli/child_process.hpp"
#include "cli/commands.hpp"
#include "cli/python_tools.hpp"
#include "cli/study_runner.hpp"
#include "cli/study_state.hpp"

namespace adrsph::cli {
namespace {

namespace fs = std::filesystem;
using analysis::StudyRun;

struct StudyOptions {
  std::string study_file;
  std::vector<std::string> only;
  bool resume = false, dry_run = false, rerun_changed = false;
  int jobs = 1, threads = 0;
  std::string out, report;
};

int error(const std::string& what) {
  std::cerr << "adrsph study: error: " << what << "\n";
  return kExitBadInput;
}

fs::path absolute_normal(const fs::path& p) {
  return fs::absolute(p).lexically_normal();
}

// A run started with other arguments than the study file now gives it: its results would
// not be what the study says. Empty when it matches or was not started by a study.
std::string changed_arguments(const RunFiles& f, const StudyRun& run, const fs::path& case_file) {
  if (const auto args = read_run_args(f.args); args && args->case_file != case_file.string())
    return "case " + args->case_file + " (now " + case_file.string() + ")";
  const auto sets = recorded_sets(f);  // args.json, or run.json of a run restored from a report
  if (sets && *sets != run.sets) {
    std::string was, now;
    for (const auto& s : *sets) was += " --set " + s;
    for (const auto& s : run.sets) now += " --set " + s;
    return "started with" + was + "; the study file now gives" + now;
  }
  return {};
}

void print_table(const std::vector<StudyRun>& runs, const std::vector<bool>& selected,
                 const fs::path& runs_dir, const fs::path& case_file) {
  std::size_t width = 4;
  for (std::size_t i = 0; i < runs.size(); ++i)
    if (selected[i]) width = std::max(width, runs[i].name.size());
  std::printf("%-*s  %-6s  %s\n", static_cast<int>(width), "run", "state", "--set");
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (!selected[i]) continue;
    const RunFiles f = run_files(runs_dir, runs[i].name);
    std::string sets;
    for (const auto& s : runs[i].sets) sets += (sets.empty() ? "" : " ") + s;
    const std::string changed = changed_arguments(f, runs[i], case_file);
    std::printf("%-*s  %-6s  %s%s\n", static_cast<int>(width), runs[i].name.c_str(),
                to_string(run_state(f)), sets.c_str(),
                changed.empty() ? "" : ("  [CHANGED: " + changed + "]").c_str());
  }
}

// One study per runs directory at a time: the lock is held until the process ends.
bool lock_runs_dir(const fs::path& runs_dir) {
  const int fd = ::open((runs_dir / ".study.lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  return fd >= 0 && ::flock(fd, LOCK_EX | LOCK_NB) == 0;
}

void write_report(const std::string& kind, const fs::path& runs_dir, const fs::path& report_dir) {
  const std::string name = kind + "_report.py";
  const fs::path script = tools_dir() / name;
  if (!fs::exists(script)) {
    std::printf("report: %s not found; no report\n", script.c_str());
    return;
  }
  const std::string py = find_plotting_python();
  if (py.empty()) {
    std::printf("report: no python3 with matplotlib found (set ADRSPH_PYTHON); no report\n");
    return;
  }
  const fs::path log = runs_dir / "report.log";
  std::printf("report: writing %s (log %s)\n", report_dir.c_str(), log.c_str());
  std::fflush(stdout);
  int code = 1;
  try {
    code = ChildProcess({py, script.string(), runs_dir.string(), report_dir.string()}, log).wait();
  } catch (const std::exception& e) {
    std::printf("report: %s\n", e.what());
  }
  if (code != 0)
    std::printf("report: %s failed (exit %d), see %s\n", name.c_str(), code, log.c_str());
  std::fflush(stdout);
}

// Quoted for the shell only when it needs it, so the usual command reads plainly.
std::string shell_word(const std::string& s) {
  const bool plain = !s.empty() && std::all_of(s.begin(), s.end(), [](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) ||
           std::string_view("_-+.,/=:").find(ch) != std::string_view::npos;
  });
  return plain ? s : shell_quote(s);
}

// The command that continues this study: same file, selection and runs directory.
std::string resume_command(const StudyOptions& o) {
  std::string cmd = "adrsph study " + shell_word(o.study_file) + " --resume";
  for (const auto& p : o.only) cmd += " --only " + shell_word(p);
  if (!o.out.empty()) cmd += " --out " + shell_word(o.out);
  return cmd;
}

int run_study_command(const StudyOptions& o) {
  analysis::StudyFile study;
  std::vector<StudyRun> runs;
  try {
    study = analysis::parse_study(o.study_file);
    runs = analysis::expand_study(study);
  } catch (const analysis::StudyError& e) {
    return error(e.what());
  }
  const auto patterns = analysis::split_patterns(o.only);
  std::vector<bool> selected(runs.size());
  for (std::size_t i = 0; i < runs.size(); ++i)
    selected[i] = analysis::run_selected(runs[i].name, patterns);
  for (const std::string& p : patterns)
    if (std::none_of(runs.begin(), runs.end(),
                     [&](const StudyRun& r) { return analysis::run_selected(r.name, {p}); }))
      return error("--only '" + p + "' matches no run of " + o.study_file + " (adrsph study " +
                   o.study_file + " --dry-run lists them)");

  const fs::path runs_dir = absolute_normal(
      !o.out.empty() ? fs::path(o.out) : study.runs_dir.value_or(fs::path("runs") / study.name));
  const fs::path report_dir = absolute_normal(
      !o.report.empty() ? fs::path(o.report) : study.report_dir.value_or(runs_dir / "report"));
  const fs::path case_file = absolute_normal(study.case_file);
  const int threads = o.threads > 0 ? o.threads
                                    : study.threads.value_or(static_cast<int>(
                                          std::max(1u, std::thread::hardware_concurrency())));

  if (o.dry_run) {
    std::printf("study %s: %zu runs, %ld selected; runs in %s\n\n", study.name.c_str(), runs.size(),
                static_cast<long>(std::count(selected.begin(), selected.end(), true)),
                runs_dir.c_str());
    print_table(runs, selected, runs_dir, case_file);
    return kExitOk;
  }
  if (o.resume) {
    try {
      for (const std::string& name : restore_from_report(runs_dir, report_dir, runs))
        std::printf("%s: done, restored from the report %s\n", name.c_str(),
                    (report_dir / "runs" / name).c_str());
    } catch (const std::exception& e) {
      return error(e.what());
    }
  }
  const auto present = std::find_if(runs.begin(), runs.end(), [&](const StudyRun& r) {
    return run_present(run_files(runs_dir, r.name));
  });
  if (!o.resume && present != runs.end())
    return error(runs_dir.string() + " already holds runs of this study (e.g. " + present->name +
                 "); continue them with --resume, or choose another --out");
  std::vector<std::string> changed_runs;  // made with other arguments than the study now gives
  for (const StudyRun& r : runs) {
    const std::string changed = changed_arguments(run_files(runs_dir, r.name), r, case_file);
    if (changed.empty()) continue;
    if (!o.rerun_changed)
      return error("run '" + r.name + "' in " + runs_dir.string() + " was " + changed +
                   "; run it anew with --rerun-changed (its files are moved to " +
                   (runs_dir / "stale").string() + "), or restore the study file");
    changed_runs.push_back(r.name);
  }
  std::error_code ec;
  fs::create_directories(runs_dir, ec);
  if (ec) return error("cannot create " + runs_dir.string() + ": " + ec.message());
  if (!lock_runs_dir(runs_dir))
    return error("another adrsph study is running in " + runs_dir.string());

  // --rerun-changed: runs the study file now gives other arguments are moved aside (all of
  // them: they no longer belong to the study) and the selected ones run again.
  for (const std::string& name : changed_runs) {
    try {
      const fs::path to = retire_stale_run(runs_dir, name, "changed");
      std::printf("%s: the study file now gives it other arguments: moved to %s\n", name.c_str(),
                  to.c_str());
    } catch (const std::exception& e) {
      return error(std::string("cannot move a changed run aside: ") + e.what());
    }
  }
  // Runs of an engine that computes differently (kResultsVersion) are moved aside and run
  // again: a study never mixes the numbers of two engines.
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (!selected[i] || run_state(run_files(runs_dir, runs[i].name)) != RunState::stale) continue;
    try {
      const fs::path to = retire_stale_run(runs_dir, runs[i].name);
      std::printf(
          "%s: computed by an engine of another results version (now %d): moved to %s, "
          "to be run again\n",
          runs[i].name.c_str(), kResultsVersion, to.c_str());
    } catch (const std::exception& e) {
      return error(std::string("cannot move a stale run aside: ") + e.what());
    }
  }

  StudySetup setup;
  setup.study = &study;
  setup.runs = &runs;
  setup.selected = selected;
  setup.study_file = o.study_file;
  setup.resume_command = resume_command(o);
  setup.runs_dir = runs_dir;
  setup.case_file = case_file;
  setup.exe = self_executable();
  setup.jobs = o.jobs;
  setup.threads_per_run = std::max(1, threads / o.jobs);
  const auto n_selected = std::count(selected.begin(), selected.end(), true);
  std::printf("study %s: %zu runs, %ld selected; %d at once, %d threads each; runs in %s\n",
              study.name.c_str(), runs.size(), static_cast<long>(n_selected), setup.jobs,
              setup.threads_per_run, runs_dir.c_str());
  std::fflush(stdout);
  const int code = run_study(setup);
  // A report is written from RUNS_DIR alone: one written while the report holds done runs
  // that RUNS_DIR lacks (a fresh runs directory started without --resume) would delete them.
  if (const auto kept = report_only_runs(runs_dir, report_dir, runs); !kept.empty())
    std::printf(
        "report: not written: %s holds %zu done run(s) that %s lacks (e.g. %s), and a "
        "report from %s would drop them; continue with --resume, which takes them back "
        "first: %s\n",
        report_dir.c_str(), kept.size(), runs_dir.c_str(), kept.front().c_str(), runs_dir.c_str(),
        setup.resume_command.c_str());
  else
    write_report(study.report, runs_dir, report_dir);
  return code;
}

// Errors past the study file (the file system, /proc) are I/O errors, exit 1.
int run_study_guarded(const StudyOptions& o) {
  try {
    return run_study_command(o);
  } catch (const std::exception& e) {
    std::cerr << "adrsph study: error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace

Command register_study(CLI::App& app) {
  auto o = std::make_shared<StudyOptions>();
  auto* sub = app.add_subcommand(
      "study",
      "Run a study: a matrix of runs from one study file (groups x axes of scheme, flow, Pe, "
      "dx and case keys), the reference of each Pe, compare per run, and the report "
      "(tools/study_report.py, or tools/stress_report.py for a study file with report = "
      "\"stress\"). Format: cases/README.md");
  // `adrsph stress cases/stress_study.toml` reads as what it does; the study file says which
  // report it gets.
  sub->alias("stress");
  sub->footer(
      "Each run is `adrsph run` in RUNS_DIR/<name>, its output in RUNS_DIR/<name>.log; the\n"
      "references go to RUNS_DIR/reference/pe<Pe>; RUNS_DIR/study.json lists every run and its\n"
      "state. Done runs are skipped; an interrupted run (a checkpoint in <name>.partial/) is\n"
      "continued. Ctrl-C or SIGTERM: the running runs write a checkpoint and stop; continue\n"
      "with --resume.\n"
      "Exit codes: 0 all selected runs done and ok, 1 I/O error or a reference failed, 2 bad\n"
      "input (study file, case keys, options, or a run reported bad input), 3 a run failed,\n"
      "4 interrupted.\n"
      "Example: adrsph study cases/paper_study.toml --only 'prescribed-*' --jobs 2");
  sub->add_option("study", o->study_file, "Study file (TOML)")->required();
  sub->add_option("--only", o->only,
                  "Run only the runs whose name matches this glob (fnmatch; repeatable or "
                  "comma-separated, e.g. --only 'paper-*-pe1000-*,ale-*')")
      ->allow_extra_args(false);
  sub->add_flag("--resume", o->resume,
                "Continue a study whose runs directory already holds runs (without it the "
                "study refuses to start there)");
  sub->add_flag("--rerun-changed", o->rerun_changed,
                "Runs made with other arguments than the study file now gives them: move their "
                "files to RUNS_DIR/stale/<name>.changed/ and run them again (without it the "
                "study stops, naming the run)");
  sub->add_option("--jobs,-j", o->jobs, "Runs at once (default 1)")
      ->check(CLI::Range(1, kMaxThreads));
  sub->add_option("--threads", o->threads,
                  "Threads in all (default: the study file's `threads`, else all cores); each "
                  "run gets max(1, threads / jobs)")
      ->check(CLI::Range(1, kMaxThreads));
  sub->add_option("--out", o->out, "Runs directory (default: the study file's runs_dir)")
      ->check(kNonEmptyPath);
  sub->add_option("--report", o->report,
                  "Report directory (default: the study file's report_dir, else RUNS_DIR/report)")
      ->check(kNonEmptyPath);
  sub->add_flag("--dry-run", o->dry_run,
                "Print the runs (name, state: done, resume or new, and --set) and exit");
  return {sub, [o] { return run_study_guarded(*o); }};
}

}  // namespace adrsph::cli
