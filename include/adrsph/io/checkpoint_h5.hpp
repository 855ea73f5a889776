// Checkpoint files (HDF5): a run in progress, with the case it runs, so that
// `adrsph run --restart DIR` can continue it. Layout:
//   /case     uint8 datasets case_text (the case file as it was read), case_file (its path),
//             overrides (the --set values, one per line); attribute threads
//   /solver   the particle store's state arrays under their names in its field list
//             (x, y, vx, vy, rho, c double; p float; kind uint8; a network's c_1 ...;
//             the conventional scheme's predicted_density float), inflow_row_tail;
//             counters and the species ledger as attributes; phase_seconds
//   /run      steady-test samples, history, average window, check clock, wall times, warm
//             start, restarts, peak RSS
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "adrsph/checkpoint.hpp"

namespace adrsph {

struct CheckpointFile {
  RunCheckpoint state;
  std::string case_file;               // the case file's path as given to `run`
  std::string case_text;               // its contents when the run started
  std::vector<std::string> overrides;  // the --set key=value strings
  int threads = 0;                     // threads of the run (bit-identical restarts need the same)
};

// Writes `file` whole or not at all (a temporary file renamed over it). Throws
// std::runtime_error naming the file.
void write_checkpoint(const std::filesystem::path& file, const CheckpointFile& cp);
// The same with the state given apart (about.state is not read): a running solver's
// checkpoint is written from its snapshot, which views the particle store, without a copy.
void write_checkpoint(const std::filesystem::path& file, const CheckpointFile& about,
                      const RunCheckpoint& state);
// Throws std::runtime_error naming the file and what is missing or malformed.
CheckpointFile read_checkpoint(const std::filesystem::path& file);

}  // namespace adrsph
