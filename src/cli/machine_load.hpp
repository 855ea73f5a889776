// How busy the machine is when a run starts: `adrsph run` warns when its threads will share
// cores with other work (cmd_run.cpp).
#pragma once

#include <sys/types.h>

namespace adrsph::cli {

// Threads of process `pid` that are running or ready to run (state R in
// /proc/<pid>/task/<tid>/stat); 0 when the process does not exist or /proc is unreadable.
int running_tasks(pid_t pid);

// Tasks ready to run on the machine right now besides this process and its parent
// (/proc/loadavg's runnable count); -1 when unknown.
int other_runnable();

// The machine's 1-minute load average; -1 when unknown.
double load_average();

}  // namespace adrsph::cli
