// The table of every case-file key: its dotted name, the type it expects and where it goes in
// Case. Shared by the TOML loader and the --set overrides (internal to src/case).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <toml++/toml.h>

#include "adrsph/case.hpp"

namespace adrsph::case_detail {

// Where a value came from, for error messages. `raw` is the text of a --set value: string
// keys take it verbatim when it does not parse as a TOML string.
struct ValueSource {
  std::string file;  // case file path, or "--set"
  std::string key;   // dotted key
  std::optional<std::string> raw;
};

struct KeyDef {
  std::string key;       // dotted, e.g. "species.D"
  std::string expected;  // human form of the type, e.g. "a number"
  std::function<void(Case&, const toml::node&, const ValueSource&)> set;
};

// Every valid key, in the order of cases/README.md.
const std::vector<KeyDef>& case_keys();
const KeyDef* find_key(const std::string& dotted);
// True for a table name that holds keys ("species", ...).
bool is_section(const std::string& dotted);

// "unknown key; did you mean 'species.D'?" (or the list of valid keys when nothing is close).
std::string unknown_key_message(const std::string& dotted);

// Short description of a TOML value for messages: "string \"abc\"", "integer 3", ...
std::string describe(const toml::node& n);

}  // namespace adrsph::case_detail
