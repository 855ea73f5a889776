// Helpers for the case, CLI and output tests: temporary directories, files, running adrsph.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace adrsph::test {

// A fresh directory under the system temp dir, removed at the end of the test.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name =
        std::string("adrsph_") + (info ? info->name() : "test") + "_" + std::to_string(::getpid());
    for (char& ch : name)
      if (ch == '/') ch = '_';
    path_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& s) const { return path_ / s; }

 private:
  std::filesystem::path path_;
};

inline void write_file(const std::filesystem::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << text;
}

inline std::string read_file(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline std::filesystem::path source_dir() {
  return ADRSPH_SOURCE_DIR;
}

// 'SOURCE/cases/NAME', quoted for a command line (built by appends: GCC 12 -Wrestrict
// misfires on "'" + string + "'").
inline std::string case_arg(const char* name) {
  std::string s(1, '\'');
  s += (source_dir() / "cases" / name).string();
  s += '\'';
  return s;
}

struct CommandResult {
  int exit_code = -1;
  std::string out, err;
};

// Runs a shell command line inside `dir` (stdout and stderr captured).
inline CommandResult run_shell(const std::string& command, const std::filesystem::path& dir) {
  const auto out = dir / "stdout.txt";
  const auto err = dir / "stderr.txt";
  // Built by appends: GCC 12 -Wrestrict misfires on long chains of string + string.
  std::string cmd = "cd '";
  cmd += dir.string();
  cmd += "' && ( ";
  cmd += command;
  cmd += " ) > '";
  cmd += out.string();
  cmd += "' 2> '";
  cmd += err.string();
  cmd += "' < /dev/null";
  const int status = std::system(cmd.c_str());
  CommandResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_file(out);
  r.err = read_file(err);
  std::filesystem::remove(out);
  std::filesystem::remove(err);
  return r;
}

// Runs the built adrsph with `args` (already shell-quoted where needed) inside `dir`.
inline CommandResult run_adrsph(const std::string& args, const std::filesystem::path& dir) {
  std::string cmd(1, '\'');
  cmd += ADRSPH_BINARY;
  cmd += "' ";
  cmd += args;
  return run_shell(cmd, dir);
}

// The keys of run.json that later tools read (README, output contract).
inline const std::vector<const char*> kRunJsonKeys = {"case",
                                                      "case_file",
                                                      "scheme",
                                                      "flow",
                                                      "Pe",
                                                      "D",
                                                      "k",
                                                      "dx",
                                                      "particles",
                                                      "fluid_particles",
                                                      "threads",
                                                      "t_end",
                                                      "t_reached",
                                                      "steps",
                                                      "wall_seconds",
                                                      "particle_steps_per_second",
                                                      "list_rebuilds",
                                                      "list_two_pass_builds",
                                                      "mean_neighbours",
                                                      "dt",
                                                      "steady",
                                                      "t_steady",
                                                      "lost_particles",
                                                      "status",
                                                      "message",
                                                      "probe_interpolation",
                                                      "average_window",
                                                      "phase_seconds",
                                                      "stations",
                                                      "overrides",
                                                      "load_average",
                                                      "ale",
                                                      "wall_images",
                                                      "peak_rss_bytes",
                                                      "engine_bytes",
                                                      "restarts",
                                                      "species_balance",
                                                      "steady_criterion",
                                                      "results_version"};

}  // namespace adrsph::test
