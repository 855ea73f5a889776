#include "cli/machine_load.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

namespace adrsph::cli {

int running_tasks(pid_t pid) {
  std::error_code ec;
  int n = 0;
  const auto tasks = std::filesystem::path("/proc") / std::to_string(pid) / "task";
  for (const auto& task : std::filesystem::directory_iterator(tasks, ec)) {
    std::ifstream stat(task.path() / "stat");
    std::string line;
    if (!std::getline(stat, line)) continue;  // the thread ended meanwhile
    // "tid (comm) S ...": comm may hold spaces and parentheses; the state follows the last ')'.
    const auto close = line.rfind(')');
    if (close != std::string::npos && close + 2 < line.size() && line[close + 2] == 'R') ++n;
  }
  return n;
}

// A CPU-bound neighbour is nearly always runnable; unlike the load average this count does not
// remember a run that has just ended. This process's own runnable threads (OpenMP workers
// still spinning) and its parent's (a study that has just solved its reference) are not
// neighbours: counting them warned of "2 other processes" on an idle machine.
int other_runnable() {
  std::ifstream in("/proc/loadavg");
  double l1 = 0, l5 = 0, l15 = 0;
  int runnable = 0, total = 0;
  char slash = 0;
  if (!(in >> l1 >> l5 >> l15 >> runnable >> slash >> total) || slash != '/') return -1;
  const int own = std::max(1, running_tasks(::getpid())) + running_tasks(::getppid());
  return std::max(0, runnable - own);
}

double load_average() {
  double load[1];
  return ::getloadavg(load, 1) == 1 ? load[0] : -1.0;
}

}  // namespace adrsph::cli
