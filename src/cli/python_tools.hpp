// The Python helpers the commands call (tools/*.py): where they are and which python runs
// them. Shared by `compare` (the error plot) and `study` (the report).
#pragma once

#include <filesystem>
#include <string>

namespace adrsph::cli {

// 'text' quoted for /bin/sh.
std::string shell_quote(const std::string& s);

// A Python 3 with matplotlib and numpy: $ADRSPH_PYTHON, else python3 on PATH, else
// /usr/bin/python3 (Debian's, where python3-matplotlib installs). Empty if none.
std::string find_plotting_python();

// The repository's tools/ directory (fixed at build time), e.g. tools/plot_errors.py.
std::filesystem::path tools_dir();

}  // namespace adrsph::cli
