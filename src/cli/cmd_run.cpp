// `adrsph run CASE.toml [--set key=value ...] [--out DIR] [--threads N] [--quiet]`
#include <omp.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

#include "adrsph/case.hpp"
#include "adrsph/io/fields_h5.hpp"
#include "adrsph/io/output_dir.hpp"
#include "adrsph/io/run_json.hpp"
#include "adrsph/probes.hpp"
#include "adrsph/simulation.hpp"
#include "cli/commands.hpp"
#include "cli/run_observer.hpp"
#include "cli/run_summary.hpp"

namespace adrsph::cli {
namespace {

constexpr int kExitIoError = 1;  // could not write the outputs, or an internal error

struct RunOptions {
  std::string case_file;
  std::vector<std::string> sets;
  std::string out;
  int threads = 0;
  bool quiet = false;
};

void error(const std::string& what) {
  std::cerr << "adrsph run: error: " << what << "\n";
}

// Writes everything except fields.h5 (already written by the observer) into `dir`.
// Returns the file names written.
std::vector<std::string> write_outputs(const std::filesystem::path& dir, const Case& c,
                                       const RunResult& r, const RunContext& ctx,
                                       const std::vector<FieldFrameInfo>& frames) {
  std::vector<std::string> files{"run.json"};
  write_run_json(dir / "run.json", c, r, ctx);
  if (!r.probes.x_mm.empty()) {
    write_probes_csv(dir / "probes.csv", r.probes);
    files.push_back("probes.csv");
  }
  if (!r.stations.x_mm.empty()) {
    write_stations_csv(dir / "stations.csv", r.stations);
    files.push_back("stations.csv");
  }
  if (!r.history.empty()) {
    write_history_csv(dir / "history.csv", r.history);
    files.push_back("history.csv");
  }
  if (!frames.empty()) {
    write_fields_xdmf(dir / "fields.xmf", "fields.h5", frames);
    files.push_back("fields.h5");
    files.push_back("fields.xmf");
  }
  return files;
}

int run(const RunOptions& o) {
  Case c;
  try {
    c = load_case(o.case_file, o.sets);
  } catch (const CaseError& e) {
    error(e.what());
    return kExitBadInput;
  }
  if (o.threads > 0) omp_set_num_threads(o.threads);
  const int threads = omp_get_max_threads();
  const std::filesystem::path out =
      o.out.empty() ? std::filesystem::path("runs") / c.name : std::filesystem::path(o.out);

  std::optional<StagedDir> stage;
  try {
    stage.emplace(out);
  } catch (const std::exception& e) {
    error(e.what());
    return kExitBadInput;
  }
  using Mode = CliObserver::ProgressMode;
  const Mode progress = (o.quiet || !c.output.progress) ? Mode::none
                        : ::isatty(STDERR_FILENO)       ? Mode::terminal
                                                        : Mode::log;
  CliObserver observer(stage->path() / "fields.h5", progress);

  const auto t0 = std::chrono::steady_clock::now();
  RunResult r;
  try {
    r = run_simulation(c, observer);
  } catch (const CaseError& e) {
    observer.end_progress();
    error(e.what());
    return kExitBadInput;
  } catch (const std::invalid_argument& e) {
    observer.end_progress();
    error(std::string("the case cannot be set up: ") + e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    observer.end_progress();
    error(std::string("run aborted, nothing written: ") + e.what());
    return kExitIoError;
  }
  observer.end_progress();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  SummaryInfo info{threads, wall, stage->final_path(), {}};
  try {
    const auto frames = observer.close_fields();
    const RunContext ctx{threads, wall, frames.size()};
    info.files = write_outputs(stage->path(), c, r, ctx, frames);
    stage->commit();
  } catch (const std::exception& e) {
    error(std::string("cannot write the outputs: ") + e.what());
    return kExitIoError;
  }
  print_summary(std::cout, c, r, info);
  if (r.status != "ok") {
    char t[32];
    std::snprintf(t, sizeof t, "%g", r.t_reached);
    error(std::string("the run failed at t = ") + t + " s: " + r.message +
          " (outputs of the last good state are in " + info.out_dir.string() + ")");
    return kExitRunFailed;
  }
  return kExitOk;
}

}  // namespace

Command register_run(CLI::App& app) {
  auto opts = std::make_shared<RunOptions>();
  auto* sub = app.add_subcommand("run", "Run one SPH simulation of a case file");
  sub->footer(
      "Writes DIR/run.json, probes.csv, stations.csv, fields.h5 and fields.xmf (see README.md).\n"
      "The outputs are written into DIR.partial-<pid> and replace DIR only at the end, so a run\n"
      "that fails at start-up leaves an existing DIR untouched. A run that fails numerically\n"
      "still writes the last good state and exits 3.\n"
      "Exit codes: 0 ok, 1 I/O or internal error, 2 bad input (case file, key, value, option),\n"
      "3 numerical failure.\n"
      "Example: adrsph run cases/lfr.toml --set scheme=conventional --set particles.dx=0.5");
  sub->add_option("case", opts->case_file, "Case file (TOML); every key: cases/README.md")
      ->required();
  sub->add_option("--set", opts->sets,
                  "Override a case key, e.g. --set species.D=0.1 --set scheme=conventional "
                  "(dotted key, TOML value; bare words are strings). Repeatable")
      ->allow_extra_args(false);
  sub->add_option("--out", opts->out, "Output directory (default: runs/<case name>)");
  sub->add_option("--threads", opts->threads,
                  "OpenMP threads (default: OMP_NUM_THREADS, else all cores)")
      ->check(CLI::PositiveNumber);
  sub->add_flag("--quiet,-q", opts->quiet, "No progress line");
  return {sub, [opts] { return run(*opts); }};
}

}  // namespace adrsph::cli
