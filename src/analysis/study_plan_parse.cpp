// Reading a study file: top-level keys, [reference], and each [[group]]'s keys as fixed
// values or axes. Case keys are not checked here (expand_study loads every run's case).
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <toml++/toml.h>

#include "analysis/study_plan.hpp"
#include "case/case_keys.hpp"

namespace adrsph::analysis {

StudyError::StudyError(const std::string& file, const std::string& where, const std::string& key,
                       const std::string& expected)
    : std::runtime_error(file + (where.empty() ? "" : ": " + where) +
                         (key.empty() ? "" : ": key '" + key + "'") + ": " + expected),
      key_(key) {}

namespace {

namespace fs = std::filesystem;
using case_detail::describe;

// A leaf of a group with its dotted key and where it is in the file (tables, inline or not,
// are flattened: `species = { ale = true }` is the key "species.ale").
struct Leaf {
  std::string key;
  const toml::node* node;
  toml::source_position pos;
};

bool before(const toml::source_position& a, const toml::source_position& b) {
  return a.line != b.line ? a.line < b.line : a.column < b.column;
}

void flatten(const toml::table& t, const std::string& prefix, std::vector<Leaf>& out,
             const std::set<std::string>& skip = {}) {
  for (const auto& [k, v] : t) {
    if (skip.count(std::string(k.str()))) continue;
    const std::string key =
        prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
    if (const auto* sub = v.as_table())
      flatten(*sub, key, out);
    else
      out.push_back({key, &v, v.source().begin});
  }
}

std::vector<Leaf> leaves_in_file_order(const toml::table& t,
                                       const std::set<std::string>& skip = {}) {
  std::vector<Leaf> out;
  flatten(t, "", out, skip);
  // toml++ keeps keys sorted by name; the matrix order follows the file.
  std::stable_sort(out.begin(), out.end(),
                   [](const Leaf& a, const Leaf& b) { return before(a.pos, b.pos); });
  return out;
}

std::string printf_g(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// A word that --set takes as a string without quotes (`scheme=modern`); anything else is
// written as a quoted TOML string.
bool bare_word(const std::string& s) {
  if (s.empty() || !std::isalpha(static_cast<unsigned char>(s[0]))) return false;
  if (s == "true" || s == "false" || s == "inf" || s == "nan") return false;
  return std::all_of(s.begin(), s.end(), [](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
  });
}

// The value as --set reads it back (TOML text).
std::string toml_text(const toml::node& n) {
  if (const auto* s = n.as_string()) {
    if (bare_word(s->get())) return s->get();
  }
  if (const auto* f = n.as_floating_point()) return format_exact(f->get());
  std::ostringstream os;
  n.visit([&os](const auto& v) { os << toml::toml_formatter{v}; });
  return os.str();
}

// Letters, digits and `_ - . +`: what a case name (and so a directory name) may hold.
bool name_chars_ok(const std::string& s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](char ch) {
    return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-' || ch == '.' ||
           ch == '+';
  });
}

bool scalar(const toml::node& n) {
  return n.is_string() || n.is_integer() || n.is_floating_point() || n.is_boolean();
}

class GroupReader {
 public:
  GroupReader(std::string file, std::string where)
      : file_(std::move(file)), where_(std::move(where)) {}

  [[noreturn]] void fail(const std::string& key, const std::string& expected) const {
    throw StudyError(file_, where_, key, expected);
  }

  // The values of a key: one for a scalar, each element of a list (an axis).
  std::vector<const toml::node*> elements(const Leaf& l, bool& axis) const {
    std::vector<const toml::node*> out;
    axis = l.node->is_array();
    if (!axis) {
      out.push_back(l.node);
      return out;
    }
    const auto& arr = *l.node->as_array();
    if (arr.empty()) fail(l.key, "expected a non-empty list (an axis), got an empty array");
    for (const auto& e : arr) out.push_back(&e);
    return out;
  }

  StudyKey word_key(const Leaf& l) const {  // scheme, flow
    StudyKey k{l.key, {}, false};
    for (const auto* e : elements(l, k.axis)) {
      if (!e->is_string())
        fail(l.key, "expected a string or a list of strings, got " + describe(*e));
      const std::string v = e->as_string()->get();
      if (!name_chars_ok(v))
        fail(l.key, "expected a word (letters, digits, _ - . +), got \"" + v + "\"");
      k.values.push_back({toml_text(*e), v, 0.0});
    }
    return k;
  }

  StudyKey number_key(const Leaf& l) const {  // Pe, dx
    StudyKey k{l.key, {}, false};
    for (const auto* e : elements(l, k.axis)) {
      const auto v = e->is_number() ? e->value<double>() : std::nullopt;
      if (!v || !(*v > 0) || !std::isfinite(*v))
        fail(l.key,
             "expected a number > 0 or a non-empty list of numbers > 0, got " + describe(*e));
      const std::string label = l.key == "Pe" ? "pe" + format_pe(*v) : "dx" + printf_g(*v);
      k.values.push_back({format_exact(*v), label, *v});
    }
    return k;
  }

  StudyKey case_key(const Leaf& l) const {  // any dotted case key
    StudyKey k{l.key, {}, false};
    const std::string last = l.key.substr(l.key.rfind('.') + 1);
    for (const auto* e : elements(l, k.axis)) {
      if (!scalar(*e))
        fail(l.key, "expected a value (string, number, boolean) or a list of them (an axis), got " +
                        describe(*e) + "; put array values in `set`");
      std::string label;
      if (const auto* s = e->as_string())
        label = s->get();
      else if (const auto* b = e->as_boolean())
        label = b->get() ? "true" : "false";
      else if (const auto* f = e->as_floating_point())
        label = printf_g(f->get());
      else
        label = std::to_string(e->as_integer()->get());
      if (k.axis && !name_chars_ok(label))
        fail(l.key,
             "an axis value must make a valid run name part (letters, digits, _ - . +), got " +
                 describe(*e));
      k.values.push_back({toml_text(*e), last + label, 0.0});
    }
    return k;
  }

 private:
  std::string file_, where_;
};

// The case key a group key overrides: two keys naming one case key cannot both be given.
std::string case_key_of(const std::string& key) {
  if (key == "dx") return "particles.dx";
  if (key == "Pe") return "species.D";
  return key;
}

StudyGroup read_group(const toml::table& g, std::size_t index, const std::string& file) {
  StudyGroup group;
  std::string where = "group " + std::to_string(index + 1);
  const auto* name = g.get("name");
  if (!name || !name->is_string())
    throw StudyError(file, where, "name",
                     name ? "expected a string, got " + describe(*name)
                          : "missing: every [[group]] needs a name");
  group.name = name->as_string()->get();
  if (!name_chars_ok(group.name) || group.name[0] == '.' || group.name[0] == '-')
    throw StudyError(
        file, where, "name",
        "expected letters, digits, _ - . + (not starting with . or -), got \"" + group.name + "\"");
  where = "group '" + group.name + "'";
  const GroupReader reader(file, where);

  std::map<std::string, std::string> given;  // case key -> the group key that sets it
  auto claim = [&](const std::string& key, const std::string& as) {
    const std::string ck = case_key_of(key);
    if (const auto it = given.find(ck); it != given.end())
      reader.fail(as, "sets " + ck + ", which '" + it->second + "' sets already");
    given[ck] = as;
  };
  if (const auto* set = g.get("set")) {
    if (!set->is_table())
      reader.fail(
          "set", "expected a table of case keys, e.g. set = { \"time.warm_start\" = false }, got " +
                     describe(*set));
    for (const Leaf& l : leaves_in_file_order(*set->as_table())) {
      claim(l.key, "set." + l.key);
      group.set.push_back(l.key + "=" + toml_text(*l.node));
    }
  }
  if (const auto* force = g.get("force")) {
    if (!force->is_boolean())
      reader.fail("force", "expected true or false, got " + describe(*force));
    group.force = force->as_boolean()->get();
  }
  for (const Leaf& l : leaves_in_file_order(g, {"name", "set", "force"})) {
    if (l.key == "scheme" || l.key == "flow")
      group.keys.push_back(reader.word_key(l));
    else if (l.key == "Pe" || l.key == "dx")
      group.keys.push_back(reader.number_key(l));
    else if (l.key.find('.') != std::string::npos)
      group.keys.push_back(reader.case_key(l));
    else
      reader.fail(l.key,
                  "unknown group key; expected name, set, force, scheme, flow, Pe, dx or a dotted "
                  "case key in quotes (\"species.ale\")");
    claim(l.key, l.key);
  }
  return group;
}

std::optional<fs::path> path_key(const toml::table& t, const char* key, const std::string& file,
                                 const fs::path& base) {
  const auto* n = t.get(key);
  if (!n) return std::nullopt;
  if (!n->is_string() || n->as_string()->get().empty())
    throw StudyError(file, "", key, "expected a path (a non-empty string), got " + describe(*n));
  return base / fs::path(n->as_string()->get());
}

int int_key(const toml::table& t, const char* key, int min, const std::string& file,
            const std::string& where, int fallback) {
  const auto* n = t.get(key);
  if (!n) return fallback;
  if (!n->is_integer() || n->as_integer()->get() < min || n->as_integer()->get() > (1 << 20))
    throw StudyError(file, where, key,
                     "expected an integer >= " + std::to_string(min) + ", got " + describe(*n));
  return static_cast<int>(n->as_integer()->get());
}

void reject_unknown(const toml::table& t, const std::set<std::string>& known,
                    const std::string& file, const std::string& where, const std::string& list) {
  for (const auto& [k, v] : t)
    if (!known.count(std::string(k.str())))
      throw StudyError(file, where, std::string(k.str()), "unknown key; expected " + list);
}

}  // namespace

StudyFile parse_study_text(const std::string& text, const fs::path& file) {
  const std::string name = file.string();
  toml::table doc;
  try {
    doc = toml::parse(text, name);
  } catch (const toml::parse_error& e) {
    const auto& b = e.source().begin;
    throw StudyError(name + ":" + std::to_string(b.line) + ":" + std::to_string(b.column), "", "",
                     "TOML syntax error: " + std::string(e.description()));
  }
  reject_unknown(
      doc, {"name", "case", "runs_dir", "report_dir", "report", "threads", "reference", "group"},
      name, "", "name, case, runs_dir, report_dir, report, threads, [reference], [[group]]");
  StudyFile s;
  s.file = file;
  s.name = file.stem().string();
  if (const auto* n = doc.get("name")) {
    if (!n->is_string())
      throw StudyError(name, "", "name", "expected a string, got " + describe(*n));
    s.name = n->as_string()->get();
  }
  const fs::path base = file.parent_path();
  const auto case_file = path_key(doc, "case", name, base);
  if (!case_file)
    throw StudyError(name, "", "case", "missing: the base case file, relative to the study file");
  s.case_file = *case_file;
  s.runs_dir = path_key(doc, "runs_dir", name, base);
  s.report_dir = path_key(doc, "report_dir", name, base);
  if (doc.get("threads")) s.threads = int_key(doc, "threads", 1, name, "", 1);
  if (const auto* r = doc.get("report")) {
    if (!r->is_string() || (r->as_string()->get() != "study" && r->as_string()->get() != "stress"))
      throw StudyError(name, "", "report",
                       "expected \"study\" (the paper's tables) or \"stress\" (the stability "
                       "map), got " +
                           describe(*r));
    s.report = r->as_string()->get();
  }
  if (const auto* r = doc.get("reference")) {
    if (!r->is_table())
      throw StudyError(name, "", "reference", "expected a table [reference], got " + describe(*r));
    const auto& rt = *r->as_table();
    reject_unknown(rt, {"nx", "ny"}, name, "[reference]", "nx, ny");
    s.reference_nx = int_key(rt, "nx", 2, name, "[reference]", s.reference_nx);
    s.reference_ny = int_key(rt, "ny", 1, name, "[reference]", s.reference_ny);
  }
  const auto* groups = doc.get("group");
  if (!groups || !groups->is_array_of_tables() || groups->as_array()->empty())
    throw StudyError(name, "", "group",
                     groups ? "expected [[group]] tables, got " + describe(*groups)
                            : "missing: at least one [[group]]");
  std::set<std::string> group_names;
  for (std::size_t i = 0; i < groups->as_array()->size(); ++i) {
    s.groups.push_back(read_group(*groups->as_array()->get(i)->as_table(), i, name));
    if (!group_names.insert(s.groups.back().name).second)
      throw StudyError(name, "group '" + s.groups.back().name + "'", "name",
                       "two groups have this name");
  }
  return s;
}

StudyFile parse_study(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec))
    throw StudyError(file.string(), "", "", "cannot read the study file: no such file");
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw StudyError(file.string(), "", "", "cannot read the study file");
  return parse_study_text(text.str(), file);
}

}  // namespace adrsph::analysis
