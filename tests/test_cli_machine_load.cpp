// The busy-machine check of `adrsph run` (src/cli/machine_load.cpp): it must see this
// process's own runnable threads, so that it does not count them as other work.
#include <gtest/gtest.h>

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <thread>

#include "cli/machine_load.hpp"

namespace adrsph::cli {
namespace {

TEST(MachineLoad, CountsThisProcessesRunnableThreads) {
  // The calling thread is running while it reads /proc.
  EXPECT_GE(running_tasks(::getpid()), 1);
  // A spinning thread is running or ready to run (state R) whichever core it waits for.
  std::atomic<bool> stop{false};
  std::atomic<bool> started{false};
  std::thread spinner([&] {
    started = true;
    while (!stop.load(std::memory_order_relaxed)) {
    }
  });
  while (!started) std::this_thread::yield();
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const int with_spinner = running_tasks(::getpid());
  stop = true;
  spinner.join();
  EXPECT_GE(with_spinner, 2);
}

TEST(MachineLoad, UnknownProcessHasNoTasks) {
  // Linux pids stay below 2^22 (pid_max's limit).
  EXPECT_EQ(running_tasks(static_cast<pid_t>(1 << 23)), 0);
}

TEST(MachineLoad, ReadsTheMachine) {
  EXPECT_GE(other_runnable(), 0);
  EXPECT_GE(load_average(), 0.0);
}

}  // namespace
}  // namespace adrsph::cli
