// Child processes for `adrsph study`: start a command with its output appended to a log, poll
// or wait for its end, ask it to stop; and the study's own stop request (SIGINT, SIGTERM).
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace adrsph::cli {

class ChildProcess {
 public:
  // Starts argv[0] (looked up on PATH when it has no slash) with `argv`; stdin is /dev/null, stdout
  // and stderr are appended to `log` (created with its directory). The child gets its own
  // process group, so a Ctrl-C on the terminal reaches only the study, which then forwards
  // one SIGTERM: a run that saw both might take the second as "stop now, no checkpoint".
  // Throws std::runtime_error when it cannot be started.
  ChildProcess(const std::vector<std::string>& argv, const std::filesystem::path& log);

  pid_t pid() const { return pid_; }
  // The exit code once the child has ended (128 + signal number when a signal ended it),
  // without blocking; empty while it runs.
  std::optional<int> poll();
  // Blocks until the child has ended; a signal to the study does not cut the wait short.
  int wait();
  // Sends SIGTERM (a run writes its checkpoint and exits 4).
  void terminate();

 private:
  pid_t pid_ = -1;
  std::optional<int> code_;
};

// Catches SIGINT, SIGTERM and SIGHUP from now on: they only set the flag read by
// stop_requested() (a hangup too: the children, in their own process groups, do not see it).
void install_stop_handlers();
bool stop_requested();

// This executable's path (/proc/self/exe).
std::filesystem::path self_executable();

}  // namespace adrsph::cli
