// What RUN_DIR/run.json says of the run, by a plain key search (no JSON dependency):
// the first "Pe": <number> and "scheme": "<string>", wherever they are nested, and every
// "law" and "zones" of its reactions.
#include <cctype>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

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

// The string values of every `"key": "..."` in text.
std::vector<std::string> string_values(const std::string& text, const std::string& key) {
  std::vector<std::string> values;
  const std::string quoted = "\"" + key + "\"";
  for (std::size_t at = text.find(quoted); at != std::string::npos;
       at = text.find(quoted, at + 1)) {
    const std::size_t p = value_start(text.substr(at), key);
    if (p == std::string::npos || text[at + p] != '"') continue;
    const std::size_t end = text.find('"', at + p + 1);
    if (end != std::string::npos) values.push_back(text.substr(at + p + 1, end - at - p - 1));
  }
  return values;
}

// True when some `"zones": [...]` in text holds anything.
bool any_zone(const std::string& text) {
  const std::string quoted = "\"zones\"";
  for (std::size_t at = text.find(quoted); at != std::string::npos;
       at = text.find(quoted, at + 1)) {
    std::size_t p = value_start(text.substr(at), "zones");
    if (p == std::string::npos || text[at + p] != '[') continue;
    p += at + 1;
    while (p < text.size() && std::isspace(static_cast<unsigned char>(text[p]))) ++p;
    if (p < text.size() && text[p] != ']') return true;
  }
  return false;
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
  const std::vector<std::string> laws = string_values(text, "law");
  info.paper_kinetics =
      laws.empty() || (laws.size() == 1 && laws.front() == "first_order" && !any_zone(text));
  return info;
}

}  // namespace adrsph::analysis
