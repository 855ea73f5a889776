// `adrsph run CASE.toml [--set key=value ...] [--out DIR] [--threads N] [--quiet]`
// `adrsph run --restart DIR [--set key=value ...] [--threads N] [--quiet]`
#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <string_view>
#include <thread>

#include "adrsph/case.hpp"
#include "adrsph/io/checkpoint_h5.hpp"
#include "adrsph/io/fields_h5.hpp"
#include "adrsph/io/output_dir.hpp"
#include "adrsph/io/run_json.hpp"
#include "adrsph/probes.hpp"
#include "adrsph/simulation.hpp"
#include "cli/commands.hpp"
#include "cli/machine_load.hpp"
#include "cli/run_observer.hpp"
#include "cli/run_preflight.hpp"
#include "cli/run_summary.hpp"

namespace adrsph::cli {
namespace {

namespace fs = std::filesystem;

// Keys a continued run may change: when and how it ends and reports, never its physics.
constexpr const char* kRestartKeys[] = {"time.t_end", "time.max_steps", "time.stop_when_steady",
                                        "output.checkpoint_minutes", "output.progress"};

struct RunOptions {
  std::string case_file;
  std::vector<std::string> sets;
  std::string out;
  std::string restart;
  int threads = 0;
  bool quiet = false;
  bool force = false;
};

void error(const std::string& what) {
  std::cerr << "adrsph run: error: " << what << "\n";
}

// Set by SIGINT/SIGTERM; the run loop asks for a checkpoint and stops at the next rebuild.
volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void run_on_stop_signal(int sig) {
  g_stop_signal = sig;
}

// Writes everything except fields.h5 (already written by the observer) into `dir`.
// Returns the file names written.
std::vector<std::string> write_outputs(const fs::path& dir, const Case& c, const RunResult& r,
                                       const RunContext& ctx,
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
  if (!r.outlet.empty()) {
    write_outlet_csv(dir / "outlet.csv", r.outlet);
    files.push_back("outlet.csv");
  }
  for (std::size_t e = 0; e < r.more_outlet.size() && e < c.more_species.size(); ++e) {
    if (r.more_outlet[e].empty()) continue;
    write_outlet_csv(dir / ("outlet_" + c.more_species[e].name + ".csv"), r.more_outlet[e]);
    files.push_back("outlet_" + c.more_species[e].name + ".csv");
  }
  for (const RunResult::SpeciesProbes& sp : r.more_species) {
    write_probes_csv(dir / ("probes_" + sp.name + ".csv"), sp.probes);
    write_stations_csv(dir / ("stations_" + sp.name + ".csv"), sp.stations);
    files.push_back("probes_" + sp.name + ".csv");
    files.push_back("stations_" + sp.name + ".csv");
  }
  if (!frames.empty()) {
    std::vector<std::string> more_c;
    for (const Case::Species& sp : c.more_species) more_c.push_back("c_" + sp.name);
    write_fields_xdmf(dir / "fields.xmf", "fields.h5", frames, more_c);
    files.push_back("fields.h5");
    files.push_back("fields.xmf");
  }
  return files;
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

// The run to start or continue: its case, where it came from, and its checkpoint if any.
struct RunSetup {
  Case c;
  CheckpointFile base;  // case file, text and overrides (and the state when continuing)
  bool resume = false;
  fs::path out;
};

// Throws CaseError (bad input) or std::runtime_error (unreadable checkpoint).
RunSetup prepare(const RunOptions& o) {
  RunSetup s;
  if (o.restart.empty()) {
    s.c = load_case(o.case_file, o.sets);
    s.base.case_file = o.case_file;
    s.base.case_text = read_text(o.case_file);
    s.base.overrides = o.sets;
    s.out = o.out.empty() ? fs::path("runs") / s.c.name : fs::path(o.out);
    return s;
  }
  s.resume = true;
  s.out = o.restart;
  const fs::path cp_file = StagedDir::checkpoint_path(s.out);
  if (!fs::exists(cp_file))
    throw CaseError(o.restart, "",
                    "nothing to continue: no checkpoint " + cp_file.string() +
                        " (give the --out directory of an interrupted run)");
  s.base = read_checkpoint(cp_file);
  for (const std::string& set : o.sets) {
    const std::string key = set.substr(0, set.find('='));
    bool allowed = false;
    for (const char* k : kRestartKeys) allowed = allowed || key == k;
    if (!allowed) {
      std::string list;
      for (const char* k : kRestartKeys) list += std::string(list.empty() ? "" : ", ") + k;
      throw CaseError("--set", key,
                      "cannot be changed when continuing a run (its physics would change "
                      "midway); allowed: " +
                          list);
    }
  }
  // The case as the run read it, from the checkpoint's copy, then the overrides.
  const fs::path case_copy = StagedDir::staging_path(s.out) / "case.toml";
  std::ofstream(case_copy, std::ios::binary | std::ios::trunc) << s.base.case_text;
  std::vector<std::string> sets = s.base.overrides;
  sets.insert(sets.end(), o.sets.begin(), o.sets.end());
  s.c = load_case(case_copy, sets);
  s.c.source = s.base.case_file;
  s.base.overrides = sets;
  return s;
}

// The CLI observer plus checkpoints: every output.checkpoint_minutes of wall time, and on a
// stop signal.
class CheckpointingObserver : public CliObserver {
 public:
  CheckpointingObserver(fs::path fields, ProgressMode progress, bool append, fs::path checkpoint,
                        const CheckpointFile& base, double minutes)
      : CliObserver(std::move(fields), progress, append),
        checkpoint_(std::move(checkpoint)),
        base_(base),
        interval_s_(60.0 * minutes) {
    // What the checkpoint says about the run, without the state it was continued from: that
    // would be a second copy of the particles held to the end of the run.
    base_.state = RunCheckpoint{};
  }

  CheckpointRequest checkpoint_request(double wall_s) override {
    if (g_stop_signal != 0) return CheckpointRequest::write_and_stop;
    if (interval_s_ > 0 && wall_s - last_s_ >= interval_s_) {
      last_s_ = wall_s;
      return CheckpointRequest::write;
    }
    return CheckpointRequest::none;
  }
  void on_checkpoint(const RunCheckpoint& cp) override {
    write_checkpoint(checkpoint_, base_, cp);  // cp views the solver's particles
    ++written_;
    if (g_stop_signal == 0) log_line("checkpoint at t = " + std::to_string(cp.solver.t) + " s");
  }
  int written() const { return written_; }

 private:
  fs::path checkpoint_;
  CheckpointFile base_;
  double interval_s_, last_s_ = 0.0;
  int written_ = 0;
};

int run(const RunOptions& o) {
  if (o.restart.empty() == o.case_file.empty()) {
    error(o.restart.empty() ? "give a case file, or --restart DIR to continue a run"
                            : "give either a case file or --restart DIR, not both");
    return kExitBadInput;
  }
  if (!o.restart.empty() && !o.out.empty()) {
    error("--restart DIR continues the run in DIR: --out does not apply");
    return kExitBadInput;
  }
  RunSetup setup;
  try {
    setup = prepare(o);
  } catch (const CaseError& e) {
    error(e.what());
    return kExitBadInput;
  } catch (const std::exception& e) {
    error(std::string("cannot continue the run: ") + e.what());
    return kExitBadInput;
  }
  const Case& c = setup.c;
  // Memory, cost and a fixed step's stability, before anything is allocated or written.
  if (const auto p = preflight(c, available_memory_bytes()); p && !(p->forceable && o.force)) {
    // Blamed on --set when the key came from there, as the case loader does.
    const auto& sets = setup.base.overrides;
    const bool from_set = std::any_of(sets.begin(), sets.end(), [&](const std::string& s) {
      return s.rfind(p->key + "=", 0) == 0;
    });
    const std::string source = c.source.empty() ? std::string("<case>") : c.source.string();
    error(CaseError(from_set ? "--set" : source, p->key, p->message).what());
    return kExitBadInput;
  }
  // A continued run repeats the interrupted one exactly with the same thread count.
  const int wanted = o.threads > 0 ? o.threads : (setup.resume ? setup.base.threads : 0);
  if (wanted > 0) omp_set_num_threads(wanted);
  const int threads = omp_get_max_threads();
  setup.base.threads = threads;

  std::optional<StagedDir> stage;
  try {
    stage.emplace(setup.out, setup.resume ? StagedDir::Mode::resume : StagedDir::Mode::fresh);
    if (stage->removed_stale())
      std::fprintf(stderr,
                   "adrsph run: note: removed %s, left by an earlier run into the same directory "
                   "that stopped without a checkpoint\n",
                   stage->path().c_str());
    if (!setup.resume)
      std::ofstream(stage->path() / "case.toml", std::ios::binary) << setup.base.case_text;
  } catch (const std::exception& e) {
    error(e.what());
    return kExitBadInput;
  }
  const fs::path checkpoint = stage->path() / "checkpoint.h5";
  using Mode = CliObserver::ProgressMode;
  const Mode progress = (o.quiet || !c.output.progress) ? Mode::none
                        : ::isatty(STDERR_FILENO)       ? Mode::terminal
                                                        : Mode::log;
  const fs::path fields = stage->path() / "fields.h5";
  CheckpointingObserver observer(fields, progress, setup.resume && fs::exists(fields), checkpoint,
                                 setup.base, c.output.checkpoint_minutes);

  g_stop_signal = 0;
  std::signal(SIGINT, run_on_stop_signal);
  std::signal(SIGTERM, run_on_stop_signal);
  const auto t0 = std::chrono::steady_clock::now();
  const double load_start = load_average();
  // Every neighbour pass ends at a barrier, and OpenMP threads spin there before they sleep:
  // on a machine whose cores are busy, a thread that shares one waits a scheduler slice at
  // each barrier. Measured next to one busy process on 2 cores (coarse reactor, 300 steps):
  // 1 thread 0.82 s, 2 threads 28 s, 2 threads with OMP_WAIT_POLICY=passive 0.93 s. On an
  // idle machine passive waiting costs up to a third at coarse resolution, so it is the
  // user's call (README.md, "Running a case"). The policy is read when the OpenMP runtime
  // starts, before this code: say so instead of running slowly.
  const int cores = static_cast<int>(std::thread::hardware_concurrency());
  const char* policy = std::getenv("OMP_WAIT_POLICY");
  const bool passive = policy && std::string_view(policy) == "passive";
  const int others = other_runnable();
  if (!o.quiet && threads > 1 && !passive && cores > 0 && others >= 0 && others + threads > cores)
    std::fprintf(stderr,
                 "adrsph run: warning: %d threads on %d cores while %d other process(es) are "
                 "running: threads that share a core wait for each other at every pass (up to "
                 "30x slower); set OMP_WAIT_POLICY=passive or use --threads %d\n",
                 threads, cores, others, std::max(1, cores - others));
  RunResult r;
  try {
    r = run_simulation(c, observer, setup.resume ? &setup.base.state : nullptr);
  } catch (const RunInterrupted& e) {
    observer.end_progress();
    error(std::string(e.what()) + "; nothing to continue: start the run again");
    return kExitInterrupted;
  } catch (const WarmStartFailed& e) {
    observer.end_progress();
    error(e.what());
    return kExitRunFailed;
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
    error(std::string("run aborted: ") + e.what());
    if (observer.written() > 0 || setup.resume) stage->keep();  // an earlier checkpoint stays
    return kExitIoError;
  }
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  observer.end_progress();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  if (r.status == "interrupted") {
    observer.close_fields();
    stage->keep();
    char t[32];
    std::snprintf(t, sizeof t, "%g", r.t_reached);
    std::cerr << "adrsph run: interrupted at t = " << t << " s (step " << r.steps
              << "); checkpoint written to " << checkpoint.string()
              << "\n  continue with: adrsph run --restart " << stage->final_path().string() << "\n";
    return kExitInterrupted;
  }

  SummaryInfo info{threads, wall, stage->final_path(), {}};
  try {
    const auto frames = observer.close_fields();
    const RunContext ctx{threads,    wall,          frames.size(), setup.base.overrides,
                         load_start, load_average()};
    info.files = write_outputs(stage->path(), c, r, ctx, frames);
    info.files.push_back("case.toml");
    std::error_code ec;
    fs::remove(checkpoint, ec);  // the run is complete: nothing to continue
    // A checkpoint half-written when an earlier process of this run was killed (SIGKILL
    // during write_checkpoint leaves its .tmp; the checkpoint itself is replaced by a rename).
    fs::path partial_write = checkpoint;
    partial_write += ".tmp";
    fs::remove(partial_write, ec);
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
      "Writes DIR/run.json, probes.csv, stations.csv, history.csv, case.toml, fields.h5 and\n"
      "fields.xmf, and outlet.csv when output.outlet_interval > 0 (see README.md). The outputs are "
      "written into DIR.partial and replace DIR only\n"
      "at the end, so a run that fails at start-up leaves an existing DIR untouched. A run that\n"
      "fails numerically still writes the last good state and exits 3.\n"
      "Checkpoints: every output.checkpoint_minutes of wall time (default 10) and on SIGINT or\n"
      "SIGTERM the run writes DIR.partial/checkpoint.h5; after a signal it exits 4.\n"
      "`adrsph run --restart DIR` continues it (same result as an uninterrupted run; --set may\n"
      "change only time.t_end, time.max_steps, time.stop_when_steady and output.*).\n"
      "Exit codes: 0 ok, 1 I/O or internal error, 2 bad input (case file, key, value, option),\n"
      "3 numerical failure, 4 interrupted (checkpoint written).\n"
      "Refused at start (exit 2): a particle count that does not fit in memory, a run that could\n"
      "never end, a fixed time.dt above the stable limit (unless --force); docs/robustness.md.\n"
      "Example: adrsph run cases/lfr.toml --set scheme=conventional --set particles.dx=0.5");
  sub->add_option("case", opts->case_file, "Case file (TOML); every key: cases/README.md");
  sub->add_option("--set", opts->sets,
                  "Override a case key, e.g. --set species.D=0.1 --set scheme=conventional "
                  "(dotted key, TOML value; bare words are strings). Repeatable")
      ->allow_extra_args(false);
  sub->add_option("--out", opts->out, "Output directory (default: runs/<case name>)")
      ->check(kNonEmptyPath);
  sub->add_option("--restart", opts->restart,
                  "Continue the interrupted run whose output directory is DIR (its checkpoint "
                  "DIR.partial/checkpoint.h5 holds the case)")
      ->check(kNonEmptyPath);
  sub->add_option("--threads", opts->threads,
                  "OpenMP threads (default: OMP_NUM_THREADS, else all cores; with --restart: "
                  "the interrupted run's)")
      ->check(CLI::Range(1, kMaxThreads));
  sub->add_flag("--quiet,-q", opts->quiet, "No progress line");
  sub->add_flag("--force", opts->force,
                "Run a fixed time.dt above the stable limit anyway (refused otherwise)");
  return {sub, [opts] { return run(*opts); }};
}

}  // namespace adrsph::cli
