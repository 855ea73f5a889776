// The key table: one line per case-file key, with a typed reader for each kind of value.
#include "case/case_keys.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <sstream>

namespace adrsph::case_detail {
namespace {

[[noreturn]] void fail(const ValueSource& src, const std::string& expected, const toml::node& n) {
  throw CaseError(src.file, src.key, "expected " + expected + ", got " + describe(n));
}

// A --set value that TOML did not read as a number (".5", "1.") may still be one.
std::optional<double> raw_number(const ValueSource& src) {
  if (!src.raw) return std::nullopt;
  const std::string& s = *src.raw;
  double v = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc{} || end != s.data() + s.size()) return std::nullopt;
  return v;
}

double read_number(const toml::node& n, const ValueSource& src) {
  double v = 0.0;
  if (const auto* f = n.as_floating_point())
    v = f->get();
  else if (const auto* i = n.as_integer())
    v = static_cast<double>(i->get());
  else if (const auto r = raw_number(src))
    v = *r;
  else
    fail(src, "a number", n);
  if (!std::isfinite(v)) fail(src, "a finite number", n);
  return v;
}

std::int64_t read_integer(const toml::node& n, const ValueSource& src, std::int64_t lo,
                          std::int64_t hi) {
  const auto* i = n.as_integer();
  if (!i) fail(src, "an integer", n);
  const std::int64_t v = i->get();
  if (v < lo || v > hi) fail(src, "an integer that fits in " + std::to_string(hi), n);
  return v;
}

bool read_bool(const toml::node& n, const ValueSource& src) {
  if (const auto* b = n.as_boolean()) return b->get();
  if (src.raw && (*src.raw == "true" || *src.raw == "false")) return *src.raw == "true";
  fail(src, "a boolean (true or false)", n);
}

std::string read_string(const toml::node& n, const ValueSource& src) {
  if (const auto* s = n.as_string()) return s->get();
  if (src.raw) return *src.raw;
  fail(src, "a string", n);
}

std::vector<double> read_number_list(const toml::node& n, const ValueSource& src) {
  const auto* a = n.as_array();
  if (!a) fail(src, "an array of numbers, e.g. [1.0, 5.0]", n);
  std::vector<double> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    ValueSource item = src;
    item.key = src.key + "[" + std::to_string(i) + "]";
    item.raw.reset();
    out.push_back(read_number(*a->get(i), item));
  }
  return out;
}

// [[a, b, ...], ...]: arrays of N numbers each. `one` names an element ("a pair [t, C] of
// two numbers"), `many` the array ("[t, C] pairs") for the messages.
template <std::size_t N>
std::vector<std::array<double, N>> read_tuples(const toml::node& n, const ValueSource& src,
                                               const std::string& one, const std::string& many,
                                               const std::string& example) {
  const auto* a = n.as_array();
  if (!a) fail(src, "an array of " + many + ", e.g. " + example, n);
  std::vector<std::array<double, N>> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    ValueSource item = src;
    item.key = src.key + "[" + std::to_string(i) + "]";
    item.raw.reset();
    const auto* tuple = a->get(i)->as_array();
    if (!tuple || tuple->size() != N) fail(item, one, *a->get(i));
    std::array<double, N> v{};
    for (std::size_t j = 0; j < N; ++j) {
      ValueSource part = item;
      part.key = item.key + "[" + std::to_string(j) + "]";
      v[j] = read_number(*tuple->get(j), part);
    }
    out.push_back(v);
  }
  return out;
}

// The [[reaction]] tables (or an inline array of tables from --set): each table's keys and
// their types here, their ranges in case_validate.cpp. The enum order must match RateLaw.
std::vector<Reaction> read_reactions(const toml::node& n, const ValueSource& src) {
  const auto* a = n.as_array();
  if (!a) fail(src, "an array of tables ([[reaction]] sections)", n);
  const std::vector<std::string> laws = {"first_order", "nth_order", "michaelis_menten",
                                         "bimolecular"};
  std::vector<Reaction> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    ValueSource item = src;
    item.key = src.key + "[" + std::to_string(i) + "]";
    item.raw.reset();
    const auto* t = a->get(i)->as_table();
    if (!t)
      fail(item, "a table ([[reaction]] with law, k, order, km, zones, reactants, products)",
           *a->get(i));
    Reaction r;
    for (const auto& [name, v] : *t) {
      ValueSource f = item;
      f.key = item.key + "." + std::string(name.str());
      if (name == "law") {
        const std::string law = read_string(v, f);
        const auto it = std::find(laws.begin(), laws.end(), law);
        if (it == laws.end())
          throw CaseError(f.file, f.key,
                          "expected one of \"first_order\" | \"nth_order\" | "
                          "\"michaelis_menten\" | \"bimolecular\", got \"" +
                              law + "\"");
        r.law = static_cast<RateLaw>(it - laws.begin());
      } else if (name == "k") {
        r.k = read_number(v, f);
      } else if (name == "order") {
        r.order = read_number(v, f);
      } else if (name == "km") {
        r.km = read_number(v, f);
      } else if (name == "zones") {
        for (const auto& z : read_tuples<5>(v, f, "a zone [x0, x1, y0, y1, factor]", "zones",
                                            "[[20.0, 40.0, -5.0, 5.0, 10.0]]"))
          r.zones.push_back({z[0], z[1], z[2], z[3], z[4]});
      } else if (name == "reactants" || name == "products") {
        const auto* list = v.as_array();
        if (!list) fail(f, "an array of species names, e.g. [\"A\", \"B\"]", v);
        if (name == "reactants") r.reactant_names.emplace();
        std::vector<std::string>& names = name == "reactants" ? *r.reactant_names : r.product_names;
        for (std::size_t j = 0; j < list->size(); ++j) {
          ValueSource e = f;
          e.key = f.key + "[" + std::to_string(j) + "]";
          names.push_back(read_string(*list->get(j), e));
        }
      } else {
        throw CaseError(f.file, f.key,
                        "unknown key; a [[reaction]] table has law, k, order, km, zones, "
                        "reactants and products (cases/README.md)");
      }
    }
    out.push_back(r);
  }
  return out;
}

// The [[species]] tables: each sets a species' name, D, c_in, c_init and [species.feed] with
// the readers of the single [species] table's keys (applied to a scratch case). The first
// table is Case::species, the others Case::more_species.
void read_species_list(Case& c, const toml::node& n, const ValueSource& src) {
  const auto* a = n.as_array();
  if (!a) fail(src, "a table ([species]) or an array of tables ([[species]] sections)", n);
  if (a->empty()) fail(src, "at least one [[species]] table", n);
  std::vector<Case::Species> list;
  for (std::size_t i = 0; i < a->size(); ++i) {
    ValueSource item = src;
    item.key = src.key + "[" + std::to_string(i) + "]";
    item.raw.reset();
    const auto* t = a->get(i)->as_table();
    if (!t) fail(item, "a table ([[species]] with name, D, c_in, c_init, feed)", *a->get(i));
    Case scratch;
    scratch.species = Case::Species{};
    auto apply = [&](const std::string& key, const toml::node& v, const std::string& shown) {
      const KeyDef* def = find_key(key);
      if (!def)
        throw CaseError(src.file, shown,
                        "unknown key; a [[species]] table has name, D, c_in, c_init and feed "
                        "(species.k and species.ale are for a single [species] table; give "
                        "reactions as [[reaction]] tables, cases/README.md)");
      def->set(scratch, v, ValueSource{src.file, shown, std::nullopt});
    };
    for (const auto& [name, v] : *t) {
      const std::string leaf_name(name.str());
      const std::string shown = item.key + "." + leaf_name;
      if (leaf_name == "feed") {
        const auto* feed = v.as_table();
        if (!feed) fail(ValueSource{src.file, shown, std::nullopt}, "a table ([species.feed])", v);
        for (const auto& [fk, fv] : *feed)
          apply("species.feed." + std::string(fk.str()), fv, shown + "." + std::string(fk.str()));
      } else if (leaf_name == "name" || leaf_name == "D" || leaf_name == "c_in" ||
                 leaf_name == "c_init") {
        apply("species." + leaf_name, v, shown);
      } else {
        apply("", v, shown);
      }
    }
    list.push_back(scratch.species);
  }
  c.species = list.front();
  c.species.k = 0.0;  // reactions of several species are [[reaction]] tables
  c.more_species.assign(list.begin() + 1, list.end());
}

template <class Get>
KeyDef number(std::string key, Get get) {
  return {std::move(key), "a number", [get](Case& c, const toml::node& n, const ValueSource& s) {
            get(c) = read_number(n, s);
          }};
}

template <class Get>
KeyDef integer(std::string key, Get get) {
  return {std::move(key), "an integer", [get](Case& c, const toml::node& n, const ValueSource& s) {
            auto& target = get(c);
            using T = std::remove_reference_t<decltype(target)>;
            target = static_cast<T>(
                read_integer(n, s, std::numeric_limits<T>::min(), std::numeric_limits<T>::max()));
          }};
}

template <class Get>
KeyDef boolean(std::string key, Get get) {
  return {std::move(key), "a boolean",
          [get](Case& c, const toml::node& n, const ValueSource& s) { get(c) = read_bool(n, s); }};
}

template <class Get>
KeyDef number_list(std::string key, Get get) {
  return {std::move(key), "an array of numbers",
          [get](Case& c, const toml::node& n, const ValueSource& s) {
            get(c) = read_number_list(n, s);
          }};
}

// An enum given as one of `names` (in the order of the enum's values).
template <class E, class Get>
KeyDef choice(std::string key, std::vector<std::string> names, Get get) {
  std::string allowed;
  for (const auto& nm : names) allowed += (allowed.empty() ? "" : " | ") + ("\"" + nm + "\"");
  return {std::move(key), "one of " + allowed,
          [get, names, allowed](Case& c, const toml::node& n, const ValueSource& s) {
            const std::string v = read_string(n, s);
            for (std::size_t i = 0; i < names.size(); ++i)
              if (v == names[i]) {
                get(c) = static_cast<E>(i);
                return;
              }
            throw CaseError(s.file, s.key, "expected one of " + allowed + ", got \"" + v + "\"");
          }};
}

std::vector<KeyDef> make_keys() {
  std::vector<KeyDef> k;
  k.push_back({"name", "a string", [](Case& c, const toml::node& n, const ValueSource& s) {
                 c.name = read_string(n, s);
               }});
  // The enum order must match Scheme and Flow in case.hpp.
  k.push_back(choice<Scheme>("scheme", {"modern", "conventional"},
                             [](Case& c) -> Scheme& { return c.scheme; }));
  k.push_back(
      choice<Flow>("flow", {"wcsph", "prescribed"}, [](Case& c) -> Flow& { return c.flow; }));

  k.push_back(number(
      "geometry.length", [](Case & c) -> auto& { return c.geometry.length; }));
  k.push_back(number(
      "geometry.half_width", [](Case & c) -> auto& { return c.geometry.half_width; }));

  k.push_back(number(
      "particles.dx", [](Case & c) -> auto& { return c.particles.dx; }));
  k.push_back(integer(
      "particles.wall_layers", [](Case & c) -> auto& { return c.particles.wall_layers; }));
  k.push_back(integer(
      "particles.inlet_layers", [](Case & c) -> auto& { return c.particles.inlet_layers; }));
  k.push_back(integer(
      "particles.outlet_layers", [](Case & c) -> auto& { return c.particles.outlet_layers; }));
  k.push_back(number(
      "particles.skin", [](Case & c) -> auto& { return c.particles.skin; }));
  k.push_back(number(
      "particles.jitter", [](Case & c) -> auto& { return c.particles.jitter; }));
  k.push_back(boolean(
      "particles.wall_images", [](Case & c) -> auto& { return c.particles.wall_images; }));

  k.push_back(number(
      "fluid.rho0", [](Case & c) -> auto& { return c.fluid.rho0; }));
  k.push_back(number(
      "fluid.nu", [](Case & c) -> auto& { return c.fluid.nu; }));
  k.push_back(number(
      "fluid.u_bulk", [](Case & c) -> auto& { return c.fluid.u_bulk; }));
  k.push_back(number(
      "fluid.c0_factor", [](Case & c) -> auto& { return c.fluid.c0_factor; }));
  k.push_back(number(
      "fluid.gamma", [](Case & c) -> auto& { return c.fluid.gamma; }));
  k.push_back(number(
      "fluid.background_pressure", [](Case & c) -> auto& { return c.fluid.background_pressure; }));
  k.push_back(choice<Driving>("fluid.driving", {"pressure", "body_force"},
                              [](Case& c) -> Driving& { return c.fluid.driving; }));

  k.push_back(
      {"species", "a table ([species]) or an array of tables ([[species]])",
       [](Case& c, const toml::node& n, const ValueSource& s) { read_species_list(c, n, s); }});
  k.push_back({"species.name", "a string", [](Case& c, const toml::node& n, const ValueSource& s) {
                 c.species.name = read_string(n, s);
               }});
  k.push_back(number(
      "species.D", [](Case & c) -> auto& { return c.species.D; }));
  k.push_back(number(
      "species.k", [](Case & c) -> auto& { return c.species.k; }));
  k.push_back(number(
      "species.c_in", [](Case & c) -> auto& { return c.species.c_in; }));
  k.push_back(number(
      "species.c_init", [](Case & c) -> auto& { return c.species.c_init; }));
  k.push_back(boolean(
      "species.ale", [](Case & c) -> auto& { return c.species.ale; }));
  // The enum order must match FeedShape in case.hpp.
  k.push_back(choice<FeedShape>("species.feed.shape", {"constant", "step", "pulse", "table"},
                                [](Case& c) -> FeedShape& { return c.species.feed.shape; }));
  k.push_back(number(
      "species.feed.t0", [](Case & c) -> auto& { return c.species.feed.t0; }));
  k.push_back(number(
      "species.feed.width", [](Case & c) -> auto& { return c.species.feed.width; }));
  k.push_back(number(
      "species.feed.base", [](Case & c) -> auto& { return c.species.feed.base; }));
  k.push_back({"species.feed.table", "an array of [t, C] pairs",
               [](Case& c, const toml::node& n, const ValueSource& s) {
                 c.species.feed.table = read_tuples<2>(n, s, "a pair [t, C] of two numbers",
                                                       "[t, C] pairs", "[[0.0, 0.0], [0.1, 2.0]]");
               }});

  k.push_back({"reaction", "an array of tables ([[reaction]])",
               [](Case& c, const toml::node& n, const ValueSource& s) {
                 c.reactions = read_reactions(n, s);
               }});

  k.push_back(number(
      "modern.delta", [](Case & c) -> auto& { return c.modern.delta; }));
  k.push_back(number(
      "modern.shift_eps", [](Case & c) -> auto& { return c.modern.shift_eps; }));
  k.push_back(number(
      "modern.shift_max", [](Case & c) -> auto& { return c.modern.shift_max; }));

  k.push_back(number(
      "time.t_end", [](Case & c) -> auto& { return c.time.t_end; }));
  k.push_back(integer(
      "time.max_steps", [](Case & c) -> auto& { return c.time.max_steps; }));
  k.push_back(number(
      "time.cfl", [](Case & c) -> auto& { return c.time.cfl; }));
  k.push_back(number(
      "time.viscous_number", [](Case & c) -> auto& { return c.time.viscous_number; }));
  k.push_back(number(
      "time.diffusion_number", [](Case & c) -> auto& { return c.time.diffusion_number; }));
  k.push_back(number(
      "time.dt", [](Case & c) -> auto& { return c.time.dt; }));
  k.push_back(number(
      "time.dt_factor", [](Case & c) -> auto& { return c.time.dt_factor; }));
  k.push_back(number(
      "time.check_interval", [](Case & c) -> auto& { return c.time.check_interval; }));
  k.push_back(boolean(
      "time.stop_when_steady", [](Case & c) -> auto& { return c.time.stop_when_steady; }));
  k.push_back(number(
      "time.steady_tol", [](Case & c) -> auto& { return c.time.steady_tol; }));
  k.push_back(number(
      "time.steady_window", [](Case & c) -> auto& { return c.time.steady_window; }));
  k.push_back(number(
      "time.steady_sweep_tol", [](Case & c) -> auto& { return c.time.steady_sweep_tol; }));
  k.push_back(number(
      "time.average_window", [](Case & c) -> auto& { return c.time.average_window; }));
  k.push_back(boolean(
      "time.warm_start", [](Case & c) -> auto& { return c.time.warm_start; }));
  k.push_back(boolean(
      "time.species_subcycling", [](Case & c) -> auto& { return c.time.species_subcycling; }));

  k.push_back(number_list(
      "output.field_times", [](Case & c) -> auto& { return c.output.field_times; }));
  k.push_back(boolean(
      "output.progress", [](Case & c) -> auto& { return c.output.progress; }));
  k.push_back(number(
      "output.checkpoint_minutes", [](Case & c) -> auto& { return c.output.checkpoint_minutes; }));
  k.push_back(number(
      "output.outlet_interval", [](Case & c) -> auto& { return c.output.outlet_interval; }));
  return k;
}

// Levenshtein distance, case-insensitive.
std::size_t distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (same ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

std::string leaf(const std::string& dotted) {
  const auto dot = dotted.rfind('.');
  return dot == std::string::npos ? dotted : dotted.substr(dot + 1);
}

std::string section_of(const std::string& dotted) {
  const auto dot = dotted.find('.');
  return dot == std::string::npos ? std::string{} : dotted.substr(0, dot);
}

}  // namespace

const std::vector<KeyDef>& case_keys() {
  static const std::vector<KeyDef> keys = make_keys();
  return keys;
}

const KeyDef* find_key(const std::string& dotted) {
  for (const auto& k : case_keys())
    if (k.key == dotted) return &k;
  return nullptr;
}

bool is_section(const std::string& dotted) {
  if (dotted.empty()) return false;
  for (const auto& k : case_keys())
    if (k.key.size() > dotted.size() && k.key.compare(0, dotted.size(), dotted) == 0 &&
        k.key[dotted.size()] == '.')
      return true;
  return false;
}

std::string unknown_key_message(const std::string& dotted) {
  // Score each valid key by the edit distance of the whole dotted name, or of its last part
  // (a key put in the wrong table, or at top level, still finds its home).
  const std::string* best = nullptr;
  std::size_t best_score = std::numeric_limits<std::size_t>::max();
  for (const auto& k : case_keys()) {
    const std::size_t score =
        std::min(distance(dotted, k.key), distance(leaf(dotted), leaf(k.key)) + 1);
    if (score < best_score) {
      best_score = score;
      best = &k.key;
    }
  }
  const std::size_t allowed = std::max<std::size_t>(2, leaf(dotted).size() / 2);
  if (best && best_score <= allowed) return "unknown key; did you mean '" + *best + "'?";
  // Nothing close: list the keys of the same table (or the top level).
  const std::string section = section_of(dotted);
  std::string list;
  for (const auto& k : case_keys()) {
    if (section_of(k.key) != (is_section(section) ? section : std::string{})) continue;
    list += (list.empty() ? "" : ", ") + k.key;
  }
  if (!is_section(section))
    list +=
        ", and the tables geometry, particles, fluid, species, "
        "modern, time, output";
  return "unknown key; valid keys here are " + list + " (see cases/README.md)";
}

std::string describe(const toml::node& n) {
  std::ostringstream os;
  if (const auto* s = n.as_string())
    os << "string \"" << s->get() << "\"";
  else if (const auto* i = n.as_integer())
    os << "integer " << i->get();
  else if (const auto* f = n.as_floating_point())
    os << "float " << f->get();
  else if (const auto* b = n.as_boolean())
    os << "boolean " << (b->get() ? "true" : "false");
  else if (n.is_array())
    os << "an array";
  else if (n.is_table())
    os << "a table";
  else
    os << "a date/time";
  return os.str();
}

}  // namespace adrsph::case_detail
