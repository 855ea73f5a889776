// load_case: read a TOML case file, apply --set overrides, validate.
#include <algorithm>
#include <fstream>
#include <set>
#include <sstream>

#include "case/case_keys.hpp"
#include "case/case_validate.hpp"

namespace adrsph {
namespace {

using case_detail::find_key;
using case_detail::is_section;
using case_detail::ValueSource;

struct Entry {
  std::string key;  // dotted
  const toml::node* node;
  long line;
};

// Every leaf of the document with its dotted key, in document order. Known tables are
// descended into; anything else is a leaf (and an unknown key unless it is in the key table).
void collect(const toml::table& t, const std::string& prefix, const std::string& file,
             std::vector<Entry>& out) {
  for (const auto& [k, v] : t) {
    const std::string key =
        prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    const long line = static_cast<long>(v.source().begin.line);
    // `species` is both: a [species] table of keys and an array of [[species]] tables.
    const bool descend = v.is_table()
                             ? is_section(key) || (!find_key(key) && !v.as_table()->empty())
                             : !find_key(key) && is_section(key);
    if (descend) {
      // A known table, or an unknown one: its leaves are reported with their full keys.
      if (const auto* sub = v.as_table()) {
        collect(*sub, key, file, out);
        continue;
      }
      throw CaseError(file, key,
                      "expected a table ([" + key + "]), got " + case_detail::describe(v) +
                          " (line " + std::to_string(line) + ")");
    }
    out.push_back({key, &v, line});
  }
}

void apply_entries(Case& c, std::vector<Entry> entries, const std::string& file) {
  std::stable_sort(entries.begin(), entries.end(),
                   [](const Entry& a, const Entry& b) { return a.line < b.line; });
  for (const auto& e : entries) {
    const auto* def = find_key(e.key);
    if (!def)
      throw CaseError(
          file, e.key,
          case_detail::unknown_key_message(e.key) + " (line " + std::to_string(e.line) + ")");
    def->set(c, *e.node, ValueSource{file, e.key, std::nullopt});
  }
}

std::string read_case_file(const std::filesystem::path& file) {
  const std::string name = file.string();
  std::error_code ec;
  if (!std::filesystem::exists(file, ec))
    throw CaseError(name, "", "cannot read the case file: no such file");
  if (std::filesystem::is_directory(file, ec))
    throw CaseError(name, "", "cannot read the case file: it is a directory");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw CaseError(name, "", "cannot read the case file: permission denied or unreadable");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

toml::table parse_text(const std::string& text, const std::string& name) {
  try {
    return toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    const auto& b = e.source().begin;
    throw CaseError(name + ":" + std::to_string(b.line) + ":" + std::to_string(b.column), "",
                    "TOML syntax error: " + std::string(e.description()));
  }
}

// One "key=value" override. The value is read as TOML ("0.5", "true", "[1, 2]", "\"s\"");
// text that is not TOML is taken as a string, so `--set scheme=conventional` works.
// Returns the (trimmed) key it set.
std::string apply_override(Case& c, const std::string& text) {
  const auto eq = text.find('=');
  auto trim = [](std::string s) {
    const auto b = s.find_first_not_of(" \t");
    const auto e = s.find_last_not_of(" \t");
    return b == std::string::npos ? std::string{} : s.substr(b, e - b + 1);
  };
  const std::string key = eq == std::string::npos ? trim(text) : trim(text.substr(0, eq));
  if (eq == std::string::npos || key.empty())
    throw CaseError("--set", key.empty() ? text : key,
                    "expected key=value, e.g. --set particles.dx=0.5");
  const std::string value = trim(text.substr(eq + 1));
  const auto* def = find_key(key);
  if (!def) {
    if (is_section(key))
      throw CaseError("--set", key, "is a table; set one of its keys, e.g. " + key + ".<key>=...");
    throw CaseError("--set", key, case_detail::unknown_key_message(key));
  }
  const ValueSource src{"--set", key, value};
  try {
    const toml::table t = toml::parse("v = " + value, std::string_view{"--set"});
    if (t.size() == 1 && t.contains("v")) {
      def->set(c, *t.get("v"), src);
      return key;
    }
  } catch (const toml::parse_error&) {
    // not a TOML value: a bare string
  }
  def->set(c, toml::value<std::string>(value), src);
  return key;
}

// The species names of the [[reaction]] tables as indices into Case::species_at().
void resolve_species_names(Case& c, const std::string& file) {
  auto index_of = [&](const std::string& name, const std::string& key) {
    std::string known;
    for (int s = 0; s < c.species_count(); ++s) {
      if (c.species_at(s).name == name) return s;
      known += (s ? ", \"" : "\"") + c.species_at(s).name + "\"";
    }
    throw CaseError(file, key,
                    "expected the name of a species (" + known + "), got \"" + name + "\"");
  };
  for (std::size_t i = 0; i < c.reactions.size(); ++i) {
    Reaction& r = c.reactions[i];
    const std::string key = "reaction[" + std::to_string(i) + "].";
    if (r.reactant_names) {
      r.reactants.clear();
      for (std::size_t j = 0; j < r.reactant_names->size(); ++j)
        r.reactants.push_back(
            index_of((*r.reactant_names)[j], key + "reactants[" + std::to_string(j) + "]"));
    }
    r.products.clear();
    for (std::size_t j = 0; j < r.product_names.size(); ++j)
      r.products.push_back(
          index_of(r.product_names[j], key + "products[" + std::to_string(j) + "]"));
  }
}

}  // namespace

Case load_case(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  return load_case_text(read_case_file(file), file, overrides);
}

Case load_case_text(const std::string& text, const std::filesystem::path& file,
                    const std::vector<std::string>& overrides) {
  const std::string name = file.string();
  const toml::table doc = parse_text(text, name);
  // Every key has a default, so an empty file would run the default case under the file's
  // name: more likely a file that was not saved or the wrong file.
  if (doc.empty())
    throw CaseError(name, "",
                    "the file holds no keys; expected a case (cases/README.md), e.g. a copy of "
                    "cases/lfr.toml");
  Case c;
  c.source = file;
  c.name = file.stem().string();  // `name` is optional: the file name without .toml
  std::vector<Entry> entries;
  collect(doc, "", name, entries);
  bool skin_given = false, k_given = false;
  for (const Entry& e : entries) {
    skin_given = skin_given || e.key == "particles.skin";
    k_given = k_given || e.key == "species.k";
  }
  apply_entries(c, std::move(entries), name);

  std::set<std::string> overridden;
  for (const auto& o : overrides) overridden.insert(apply_override(c, o));
  // The list skin's default depends on the flow (case.hpp, Particles::kPrescribedSkin).
  if (!skin_given && overridden.count("particles.skin") == 0 && c.flow == Flow::prescribed)
    c.particles.skin = Case::Particles::kPrescribedSkin;
  // species.k's default (1.462 1/s, the paper's) is the reaction of a case without
  // [[reaction]] tables; with them, only what they say reacts unless species.k is given.
  if (!c.reactions.empty() && !k_given && overridden.count("species.k") == 0) c.species.k = 0.0;
  // A bad species table is named as such, not as a reaction's unknown species.
  auto problem = case_detail::find_species_problem(c);
  if (!problem) {
    resolve_species_names(c, name);
    problem = case_detail::find_problem(c);
  }
  if (const auto& p = problem) {
    // A value that came from --set is blamed on --set, not on the file.
    const bool from_set = overridden.count(p->key.substr(0, p->key.find('['))) > 0;
    throw CaseError(from_set ? "--set" : name, p->key, p->expected);
  }
  return c;
}

}  // namespace adrsph
