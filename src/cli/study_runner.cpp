// The study's scheduler. Single-threaded: it starts children, polls them four times a
// second, and acts on the stop flag between polls.
#include "cli/study_runner.hpp"

#include <time.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <set>

#include "cli/child_process.hpp"
#include "cli/commands.hpp"
#include "cli/run_observer.hpp"
#include "cli/study_state.hpp"

namespace adrsph::cli {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
constexpr auto kNoteEvery = std::chrono::seconds(60);

// One line of the study's own output, flushed: it is often redirected to a file.
void say(const std::string& line) {
  std::printf("%s\n", line.c_str());
  std::fflush(stdout);
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

void pause_briefly() {
  const timespec ts{0, 250'000'000};
  ::nanosleep(&ts, nullptr);  // a signal ends it early, which is what we want
}

// The last "progress: ..." line the child wrote to its log after `from` (its start).
std::string last_progress(const fs::path& log, std::uintmax_t from) {
  std::ifstream in(log, std::ios::binary);
  if (!in) return {};
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::uintmax_t>(in.tellg());
  const std::uintmax_t start = std::max(from, size > 16384 ? size - 16384 : 0);
  in.seekg(static_cast<std::streamoff>(start));
  std::string line, last;
  while (std::getline(in, line))
    if (line.rfind("progress: ", 0) == 0) last = line;
  return last;
}

std::uintmax_t size_or_zero(const fs::path& f) {
  std::error_code ec;
  const auto n = fs::file_size(f, ec);
  return ec ? 0 : n;
}

// One line in the log before each child's own output, so a log of several attempts reads.
void log_header(const fs::path& log, const std::vector<std::string>& argv) {
  std::ofstream out(log, std::ios::binary | std::ios::app);
  const std::time_t now = std::time(nullptr);
  char when[64];
  std::strftime(when, sizeof when, "%Y-%m-%d %H:%M:%S", std::localtime(&now));
  out << "=== adrsph study, " << when << ":";
  for (const std::string& a : argv) out << " " << a;
  out << "\n";
}

class StudyRunner {
 public:
  explicit StudyRunner(const StudySetup& s) : s_(s), runs_(*s.runs) {
    for (std::size_t i = 0; i < runs_.size(); ++i)
      if (s_.selected[i]) ordinal_[i] = ++n_selected_;
  }

  int run();

 private:
  struct Active {
    std::size_t run;
    std::unique_ptr<ChildProcess> child;
    Clock::time_point started, last_note;
    std::uintmax_t log_from;
  };

  const analysis::StudyRun& R(std::size_t i) const { return runs_[i]; }
  RunFiles files(std::size_t i) const { return run_files(s_.runs_dir, R(i).name); }
  // "[3/27] paper-modern-pe1000-dx0.25". (Appending, not `"[" + ...`, avoids GCC 12's false
  // -Wrestrict on string concatenation.)
  std::string tag(std::size_t i) const {
    std::string t(1, '[');
    t += std::to_string(ordinal_.at(i));
    t += '/';
    t += std::to_string(n_selected_);
    t += "] ";
    return t + R(i).name;
  }
  fs::path reference_dir(const std::string& label) const {
    return s_.runs_dir / "reference" / ("pe" + label);
  }
  bool stopping() const { return interrupted_ || bad_input_; }

  void write_json();
  void ensure_reference(std::size_t first_run);
  void compare(std::size_t i);
  void start(std::size_t i);
  void finished(Active& a, int code);
  void note(Active& a);
  void stop_children(std::vector<Active>& active);
  int summary() const;

  const StudySetup& s_;
  const std::vector<analysis::StudyRun>& runs_;
  std::map<std::size_t, int> ordinal_;
  int n_selected_ = 0;
  std::map<std::string, std::string> failures_;  // run name -> why (no run.json to say it)
  std::set<std::string> references_ok_, references_failed_;
  bool interrupted_ = false, bad_input_ = false, forwarded_ = false;
  std::vector<Active>* active_ = nullptr;
};

void StudyRunner::write_json() {
  std::vector<StudyJsonRun> list;
  for (std::size_t i = 0; i < runs_.size(); ++i) {
    const RunFiles f = files(i);
    StudyJsonRun e{&R(i), "pending", {}};
    switch (run_state(f)) {
      case RunState::done:
        e.status = read_run_record(f.dir).status == "ok" ? "done" : "failed";
        break;
      case RunState::resume:
        e.status = "interrupted";
        break;
      case RunState::stale:  // a run not selected this time, of an older engine
        e.status = "stale";
        e.message = "computed by an engine of another results version; run it again";
        break;
      case RunState::fresh:
        if (const auto it = failures_.find(R(i).name); it != failures_.end()) {
          e.status = "failed";
          e.message = it->second;
        }
        break;
    }
    list.push_back(e);
  }
  try {
    write_study_json(s_.runs_dir, s_.study->name, s_.study_file, list);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "adrsph study: cannot write study.json: %s\n", e.what());
  }
}

void StudyRunner::ensure_reference(std::size_t first_run) {
  const std::string& label = R(first_run).pe_label;
  const fs::path dir = reference_dir(label);
  if (fs::exists(dir / "stations.csv")) {
    references_ok_.insert(label);
    return;
  }
  const std::vector<std::string> argv{s_.exe.string(),
                                      "reference",
                                      s_.case_file.string(),
                                      "--set",
                                      "species.D=" + analysis::format_exact(R(first_run).D),
                                      "--nx",
                                      std::to_string(s_.study->reference_nx),
                                      "--ny",
                                      std::to_string(s_.study->reference_ny),
                                      "--out",
                                      dir.string()};
  const fs::path log = s_.runs_dir / "reference" / ("pe" + label + ".log");
  say("reference Pe = " + label + ": started (" + std::to_string(s_.study->reference_nx) + " x " +
      std::to_string(s_.study->reference_ny) + ")");
  const auto t0 = Clock::now();
  int code = kExitIoError;
  try {
    log_header(log, argv);
    code = ChildProcess(argv, log).wait();  // a few seconds: a stop request waits for it
  } catch (const std::exception& e) {
    std::fprintf(stderr, "adrsph study: %s\n", e.what());
  }
  if (code == 0 && fs::exists(dir / "stations.csv")) {
    references_ok_.insert(label);
    say("reference Pe = " + label + ": done, " + format_hms(seconds_since(t0)));
    return;
  }
  references_failed_.insert(label);
  say("reference Pe = " + label + ": FAILED (exit " + std::to_string(code) + "), see " +
      log.string());
  if (code == 2) bad_input_ = true;
}

void StudyRunner::compare(std::size_t i) {
  const RunFiles f = files(i);
  const std::string& label = R(i).pe_label;
  if (!references_ok_.count(label)) {
    say(tag(i) + ": no compare (the reference of Pe = " + label + " is missing)");
    return;
  }
  std::error_code ec1, ec2;
  const auto csv = fs::last_write_time(f.dir / "compare.csv", ec1);
  const auto json = fs::last_write_time(f.dir / "run.json", ec2);
  if (!ec1 && !ec2 && csv > json) return;  // compared after the run ended
  const std::vector<std::string> argv{s_.exe.string(), "compare", f.dir.string(),
                                      reference_dir(label).string()};
  int code = kExitIoError;
  try {
    log_header(f.log, argv);
    code = ChildProcess(argv, f.log).wait();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "adrsph study: %s\n", e.what());
  }
  if (code != 0)
    say(tag(i) + ": compare failed (exit " + std::to_string(code) + "), see " + f.log.string());
}

void StudyRunner::start(std::size_t i) {
  const RunFiles f = files(i);
  const bool resume = run_state(f) == RunState::resume;
  std::vector<std::string> argv{s_.exe.string(), "run"};
  if (resume) {
    argv.insert(argv.end(), {"--restart", f.dir.string()});
  } else {
    argv.push_back(s_.case_file.string());
    for (const std::string& set : R(i).sets) argv.insert(argv.end(), {"--set", set});
    argv.insert(argv.end(), {"--out", f.dir.string()});
  }
  argv.insert(argv.end(), {"--threads", std::to_string(s_.threads_per_run)});
  if (R(i).force) argv.push_back("--force");
  Active a{i, nullptr, Clock::now(), Clock::now(), 0};
  try {
    if (!resume) write_run_args(f.args, argv, {s_.case_file.string(), R(i).sets});
    log_header(f.log, argv);
    a.log_from = size_or_zero(f.log);
    a.child = std::make_unique<ChildProcess>(argv, f.log);
  } catch (const std::exception& e) {
    failures_[R(i).name] = e.what();
    say(tag(i) + ": cannot start: " + e.what());
    return;
  }
  say(tag(i) + (resume ? ": resumed from its checkpoint" : ": started"));
  active_->push_back(std::move(a));
}

void StudyRunner::finished(Active& a, int code) {
  const std::size_t i = a.run;
  const RunFiles f = files(i);
  const double wall = seconds_since(a.started);
  if (code == 0 || code == 3) {
    const RunRecord r = read_run_record(f.dir);
    if (r.status.empty()) {
      failures_[R(i).name] =
          "exit " + std::to_string(code) + " without run.json, see " + f.log.filename().string();
      say(tag(i) + ": ended without run.json, see " + f.log.string());
      return;
    }
    say(tag(i) + ": " + (r.status == "ok" ? "ok" : "FAILED (" + r.message + ")") + ", wall " +
        format_hms(r.wall_seconds) + ", t_reached " + num(r.t_reached) + " s, " +
        (r.t_steady ? "steady at " + num(*r.t_steady) + " s" : std::string("not steady")));
    compare(i);
    return;
  }
  if (code == kExitInterrupted || (forwarded_ && code != 2)) {
    // Asked to stop (or stopped by someone else): not a failure. Without a checkpoint (a run
    // that cannot write one, or killed) it starts again on --resume.
    const bool checkpoint = fs::exists(f.checkpoint);
    say(tag(i) + (checkpoint ? ": interrupted, checkpoint written" : ": stopped, no checkpoint") +
        " (ran " + format_hms(wall) + " this time)");
    interrupted_ = true;
    return;
  }
  if (code == 2) {
    say(tag(i) + ": bad input (exit 2), see " + f.log.string());
    failures_[R(i).name] = "bad input, see " + f.log.filename().string();
    bad_input_ = true;
    return;
  }
  failures_[R(i).name] = "exit " + std::to_string(code) + ", see " + f.log.filename().string();
  say(tag(i) + ": ended with exit code " + std::to_string(code) + ", see " + f.log.string());
}

void StudyRunner::note(Active& a) {
  const auto now = Clock::now();
  if (now - a.last_note < kNoteEvery) return;
  a.last_note = now;
  const std::string p = last_progress(files(a.run).log, a.log_from);
  say(tag(a.run) + ": running " + format_hms(seconds_since(a.started)) +
      (p.empty() ? "" : ", " + p));
}

void StudyRunner::stop_children(std::vector<Active>& active) {
  if (forwarded_) return;
  forwarded_ = true;
  if (active.empty()) return;
  std::printf("stopping: asking %zu running run(s) to write a checkpoint and stop\n",
              active.size());
  std::fflush(stdout);
  for (Active& a : active) a.child->terminate();
}

int StudyRunner::summary() const {
  int done = 0, to_go = 0, failed = 0;
  for (std::size_t i = 0; i < runs_.size(); ++i) {
    if (!s_.selected[i]) continue;
    const RunFiles f = files(i);
    if (run_state(f) == RunState::done) {
      ++done;
      if (read_run_record(f.dir).status != "ok") ++failed;
    } else {
      ++to_go;
      if (failures_.count(R(i).name)) ++failed;
    }
  }
  if (bad_input_) {
    std::printf("study stopped on bad input: %d runs done, %d to go (see the logs in %s)\n", done,
                to_go, s_.runs_dir.c_str());
    return 2;
  }
  if (interrupted_) {
    std::printf("study interrupted: %d runs done, %d to go; continue with: %s\n", done, to_go,
                s_.resume_command.c_str());
    return kExitInterrupted;
  }
  std::printf("study finished: %d runs done (%d failed), %d to go\n", done, failed, to_go);
  if (failed > 0) return 3;
  return references_failed_.empty() ? 0 : kExitIoError;
}

int StudyRunner::run() {
  install_stop_handlers();
  std::vector<Active> active;
  active_ = &active;
  write_json();

  // References first (cheap), one per Pe of the selected runs (for their compares) and of the
  // runs already done (the report compares every done run, restored ones included), then the
  // compares of the selected runs already done.
  std::set<std::string> labels;
  for (std::size_t i = 0; i < runs_.size() && !stopping(); ++i) {
    const bool needed = s_.selected[i] || run_state(files(i)) == RunState::done;
    if (!needed || !labels.insert(R(i).pe_label).second) continue;
    ensure_reference(i);
    if (stop_requested()) interrupted_ = true;
  }
  std::vector<std::size_t> queue;
  for (std::size_t i = 0; i < runs_.size(); ++i) {
    if (!s_.selected[i]) continue;
    if (run_state(files(i)) != RunState::done)
      queue.push_back(i);
    else if (!stopping())
      compare(i);
    if (stop_requested()) interrupted_ = true;
  }

  std::size_t next = 0;
  while (next < queue.size() || !active.empty()) {
    if (stop_requested()) interrupted_ = true;
    if (stopping()) stop_children(active);
    while (!stopping() && next < queue.size() &&
           active.size() < static_cast<std::size_t>(s_.jobs)) {
      start(queue[next++]);
      write_json();
    }
    if (stopping() && active.empty()) break;
    for (std::size_t k = 0; k < active.size();) {
      if (const auto code = active[k].child->poll()) {
        finished(active[k], *code);
        active.erase(active.begin() + static_cast<long>(k));
        write_json();
        continue;
      }
      note(active[k]);
      ++k;
    }
    if (!active.empty()) pause_briefly();
  }
  write_json();
  return summary();
}

}  // namespace

int run_study(const StudySetup& s) {
  return StudyRunner(s).run();
}

}  // namespace adrsph::cli
