// Locating tools/*.py and a python3 that can plot.
#include "cli/python_tools.hpp"

#include <cstdlib>
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

}  // namespace adrsph::cli
