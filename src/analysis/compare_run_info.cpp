// What RUN_DIR/run.json says of the run, by a plain key search (no JSON dependency):
// the first "Pe": <number> and "scheme": "<string>", wherever they are nested.
#include <cctype>
#include <fstream>
#include <sstream>
#include <string>

#include "analysis/compare.hpp"

namespace adrsph::analysis {
namespace {

// Position just after `"key"` and the following ':' (skipping blanks), or npos.
std::size_t value_start(const std::string& text, const std::string& key) {
  const std::string quoted = "\"" + key + "\"";
  for (std::size_t at = text.find(quoted); at != std::string::npos;
       at = text.find(quoted, at + 1)) {
    std::size_t p = at + quoted.size();
    while (p < text.size() && std::isspace(static_cast<unsigned char>(text[p]))) ++p;
    if (p < text.size() && text[p] == ':') {
      ++p;
      while (p < text.size() && std::isspace(static_cast<unsigned char>(text[p]))) ++p;
      return p;
    }
  }
  return std::string::npos;
}

}  // namespace

RunInfo read_run_info(const std::filesystem::path& run_json) {
  RunInfo info;
  std::ifstream in(run_json, std::ios::binary);
  if (!in) return info;
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();

  if (std::size_t p = value_start(text, "Pe"); p != std::string::npos) {
    try {
      info.pe = std::stod(text.substr(p, 32));
    } catch (const std::exception&) {
    }
  }
  if (std::size_t p = value_start(text, "scheme"); p != std::string::npos && text[p] == '"') {
    const std::size_t end = text.find('"', p + 1);
    if (end != std::string::npos) info.scheme = text.substr(p + 1, end - p - 1);
  }
  return info;
}

}  // namespace adrsph::analysis
