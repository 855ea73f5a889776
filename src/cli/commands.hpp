// Each subcommand registers itself on the CLI11 app from its own file.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace adrsph::cli {

// Exit codes shared by all subcommands.
inline constexpr int kExitOk = 0;
inline constexpr int kExitIoError = 1;      // could not read or write files, or an internal error
inline constexpr int kExitBadInput = 2;     // bad case file, key, value, missing file
inline constexpr int kExitRunFailed = 3;    // numerical failure (NaN, blow-up, lost particles)
inline constexpr int kExitInterrupted = 4;  // SIGINT/SIGTERM: checkpoint written, continue later

// Largest --threads accepted: beyond it the OpenMP runtime cannot start the threads.
inline constexpr int kMaxThreads = 1024;

// A path option given as an empty string (`--out ""`) is refused rather than read as absent.
inline const CLI::Validator kNonEmptyPath(
    [](std::string& s) {
      return s.empty() ? std::string("expected a path, got an empty string") : "";
    },
    "PATH");

// Each adds its subcommand to `app` and returns it with the function to run after parsing
// when that subcommand was chosen; the function's result is the exit code.
struct Command {
  CLI::App* sub = nullptr;
  std::function<int()> action;
};
Command register_run(CLI::App& app);
Command register_reference(CLI::App& app);
Command register_compare(CLI::App& app);
Command register_study(CLI::App& app);
Command register_rtd(CLI::App& app);

}  // namespace adrsph::cli
