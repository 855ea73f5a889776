// DIR/run.json: the summary of one run (the output contract; later tools read these names).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "adrsph/case.hpp"
#include "adrsph/simulation.hpp"

namespace adrsph {

// What the run command adds to the case and the result.
struct RunContext {
  int threads = 1;
  double wall_seconds = 0.0;  // used when RunResult::wall_s is 0
  std::size_t field_frames = 0;
  std::vector<std::string> overrides;         // the --set key=value strings
  double load_start = -1.0, load_end = -1.0;  // 1-minute load average of the machine (-1: unknown)
};

// The JSON text (pretty-printed, keys in a fixed order):
// case, case_file, scheme, flow, Pe, D, k, dx, particles, fluid_particles, threads, t_end,
// t_reached, steps, wall_seconds, particle_steps_per_second,
// dt {chosen, binding, acoustic, advective, viscous, diffusion}, steady, t_steady (or null),
// lost_particles, status, message, probe_interpolation, average_window,
// phase_seconds {name: s}, stations {"25": C_mean, ...}, field_frames, version.
std::string run_json_text(const Case& c, const RunResult& r, const RunContext& ctx);

// Writes run_json_text to `file`; throws std::runtime_error naming the file on failure.
void write_run_json(const std::filesystem::path& file, const Case& c, const RunResult& r,
                    const RunContext& ctx);

}  // namespace adrsph
