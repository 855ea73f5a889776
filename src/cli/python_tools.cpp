// Locating tools/*.py and a python3 that can plot.
#include "cli/python_tools.hpp"

#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <vector>

#ifndef ADRSPH_TOOLS_DIR
#define ADRSPH_TOOLS_DIR "tools"
#endif

namespace adrsph::cli {

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char ch : s) q += ch == '\'' ? std::string("'\\''") : std::string(1, ch);
  return q + "'";
}

std::string find_plotting_python() {
  std::vector<std::string> candidates;
  if (const char* env = std::getenv("ADRSPH_PYTHON")) candidates.emplace_back(env);
  candidates.emplace_back("python3");
  candidates.emplace_back("/usr/bin/python3");
  for (const std::string& py : candidates) {
    const std::string probe = shell_quote(py) + " -c 'import matplotlib, numpy' >/dev/null 2>&1";
    if (std::system(probe.c_str()) == 0) return py;
  }
  return {};
}

std::filesystem::path tools_dir() {
  return ADRSPH_TOOLS_DIR;
}

void run_plot_script(const std::string& script, const std::vector<std::string>& args) {
  const std::filesystem::path path = tools_dir() / script;
  if (!std::filesystem::exists(path)) {
    std::printf("plot: %s not found; no PNG\n", path.c_str());
    return;
  }
  const std::string py = find_plotting_python();
  if (py.empty()) {
    std::printf("plot: no python3 with matplotlib found (set ADRSPH_PYTHON); no PNG\n");
    return;
  }
  std::string cmd = shell_quote(py);
  cmd.append(" ").append(shell_quote(path.string()));
  for (const std::string& a : args) cmd.append(" ").append(shell_quote(a));
  // The script's own output follows what this process printed so far.
  std::cout.flush();
  std::fflush(stdout);
  if (std::system(cmd.c_str()) != 0) std::printf("plot: %s failed; no PNG\n", path.c_str());
}

}  // namespace adrsph::cli
