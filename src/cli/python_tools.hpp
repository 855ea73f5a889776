// The Python helpers the commands call (tools/*.py): where they are and which python runs
// them. Shared by `compare` (the error plot) and `study` (the report).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace adrsph::cli {

// 'text' quoted for /bin/sh.
std::string shell_quote(const std::string& s);

// A Python 3 with matplotlib and numpy: $ADRSPH_PYTHON, else python3 on PATH, else
// /usr/bin/python3 (Debian's, where python3-matplotlib installs). Empty if none.
std::string find_plotting_python();

// The repository's tools/ directory (fixed at build time), e.g. tools/plot_errors.py.
std::filesystem::path tools_dir();

// Run tools/<script> with `args` (each quoted) under find_plotting_python(). A missing script,
// no plotting python or a failed plot prints why on stdout ("plot: ...; no PNG") and goes on:
// the figures are extras, never a reason for a command to fail.
void run_plot_script(const std::string& script, const std::vector<std::string>& args);

}  // namespace adrsph::cli
