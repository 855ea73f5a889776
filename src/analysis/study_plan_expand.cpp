// The matrix of a study: every run's name and --set overrides, each run's case loaded once
// so that a bad key or value fails before anything runs; --only selection.
#include <fnmatch.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <map>

#include "analysis/study_plan.hpp"

namespace adrsph::analysis {
namespace {

// The group key that put `case_key` into a run's sets: errors name what the study file says.
std::string study_key_for(const StudyGroup& g, const std::string& case_key) {
  const std::string k = case_key.substr(0, case_key.find('['));  // "output.field_times[1]"
  for (const std::string& s : g.set)
    if (s.substr(0, s.find('=')) == k) return "set." + k;
  for (const StudyKey& key : g.keys) {
    if (k == "particles.dx" && key.key == "dx") return "dx";
    if (k == "species.D" && key.key == "Pe") return "Pe";
  }
  return k;
}

// What a CaseError says was expected, without its "FILE: key 'K': " prefix.
std::string expected_part(const CaseError& e) {
  const std::string prefix = e.file() + (e.key().empty() ? "" : ": key '" + e.key() + "'") + ": ";
  const std::string what = e.what();
  return what.compare(0, prefix.size(), prefix) == 0 ? what.substr(prefix.size()) : what;
}

Case load_run_case(const StudyFile& s, const StudyGroup& g, const std::string& run,
                   const std::vector<std::string>& sets) {
  try {
    return load_case(s.case_file, sets);
  } catch (const CaseError& e) {
    if (e.file() == "--set")
      throw StudyError(s.file.string(), "group '" + g.name + "', run '" + run + "'",
                       study_key_for(g, e.key()), expected_part(e));
    throw StudyError(s.file.string(), "", "case",
                     std::string("the base case does not load: ") + e.what());
  }
}

// The reference of a Pe is solved from the base case with species.D set (one per Pe), so
// every run of that Pe must have the same physics of the steady problem.
void check_reference_physics(const StudyFile& s, const StudyGroup& g, const StudyRun& run,
                             const Case& c, const Case& ref) {
  const struct {
    const char* key;
    double run, ref;
  } fields[] = {{"species.D", c.species.D, ref.species.D},
                {"species.k", c.species.k, ref.species.k},
                {"species.c_in", c.species.c_in, ref.species.c_in},
                {"fluid.u_bulk", c.fluid.u_bulk, ref.fluid.u_bulk},
                {"geometry.length", c.geometry.length, ref.geometry.length},
                {"geometry.half_width", c.geometry.half_width, ref.geometry.half_width}};
  for (const auto& f : fields) {
    if (std::abs(f.run - f.ref) <= 1e-9 * std::max(std::abs(f.run), std::abs(f.ref))) continue;
    throw StudyError(s.file.string(), "group '" + g.name + "', run '" + run.name + "'",
                     study_key_for(g, f.key),
                     "gives " + std::string(f.key) + " = " + format_exact(f.run) +
                         ", but the reference of Pe = " + run.pe_label +
                         " is solved from the base case with only species.D set (" + f.key + " = " +
                         format_exact(f.ref) + "); change it in the base case, not per group");
  }
}

// The runs of one group, axes as nested loops in file order, the last one fastest.
void expand_group(const StudyFile& s, const StudyGroup& g, std::vector<StudyRun>& runs,
                  std::vector<Case>& cases) {
  std::size_t total = 1;
  for (const StudyKey& k : g.keys)
    if (k.axis) total *= k.values.size();
  for (std::size_t n = 0; n < total; ++n) {
    std::vector<std::size_t> pick(g.keys.size(), 0);
    std::size_t rest = n;
    for (std::size_t i = g.keys.size(); i-- > 0;) {
      if (!g.keys[i].axis) continue;
      pick[i] = rest % g.keys[i].values.size();
      rest /= g.keys[i].values.size();
    }
    StudyRun run;
    run.group = g.name;
    run.name = g.name;
    run.sets = g.set;
    run.force = g.force;
    std::optional<std::size_t> pe_at;  // where species.D goes among the sets
    double pe = 0;
    for (std::size_t i = 0; i < g.keys.size(); ++i) {
      const StudyKey& k = g.keys[i];
      const StudyValue& v = k.values[pick[i]];
      if (k.axis) run.name += "-" + v.label;
      if (k.key == "Pe") {
        pe_at = run.sets.size();
        pe = v.number;
      } else {
        run.sets.push_back((k.key == "dx" ? "particles.dx" : k.key) + "=" + v.toml);
      }
    }
    Case c = load_run_case(s, g, run.name, run.sets);
    if (pe_at) {
      // Pe is u_bulk L / D of this run's case (the group's other keys applied).
      const double D = c.fluid.u_bulk * c.geometry.length / pe;
      run.sets.insert(run.sets.begin() + static_cast<long>(*pe_at), "species.D=" + format_exact(D));
      c = load_run_case(s, g, run.name, run.sets);
    }
    run.pe = pe_at ? pe : c.peclet();
    run.D = c.species.D;
    run.pe_label = format_pe(run.pe);
    runs.push_back(std::move(run));
    cases.push_back(std::move(c));
  }
}

}  // namespace

std::string format_exact(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string format_pe(double pe) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10g", pe);
  return buf;
}

std::vector<StudyRun> expand_study(const StudyFile& s) {
  std::vector<StudyRun> runs;
  std::map<std::string, std::string> group_of;  // run name -> group
  std::map<std::string, Case> references;       // Pe label -> the reference's case
  for (const StudyGroup& g : s.groups) {
    const std::size_t first = runs.size();
    std::vector<Case> cases;  // of this group's runs
    expand_group(s, g, runs, cases);
    for (std::size_t i = first; i < runs.size(); ++i) {
      const StudyRun& r = runs[i];
      if (r.name == "reference")
        throw StudyError(s.file.string(), "group '" + g.name + "'", "name",
                         "the run name 'reference' is taken by the references' directory");
      if (const auto it = group_of.find(r.name); it != group_of.end())
        throw StudyError(s.file.string(), "group '" + g.name + "'", "name",
                         "its run '" + r.name + "' has the name of a run of group '" + it->second +
                             "'; rename a group or add an axis");
      group_of[r.name] = g.name;
      auto ref = references.find(r.pe_label);
      if (ref == references.end()) {
        const std::vector<std::string> sets{"species.D=" + format_exact(r.D)};
        ref = references.emplace(r.pe_label, load_run_case(s, g, r.name, sets)).first;
      }
      check_reference_physics(s, g, r, cases[i - first], ref->second);
    }
  }
  return runs;
}

std::vector<std::string> split_patterns(const std::vector<std::string>& args) {
  std::vector<std::string> out;
  for (const std::string& a : args) {
    std::size_t start = 0;
    while (start <= a.size()) {
      const std::size_t comma = std::min(a.find(',', start), a.size());
      if (comma > start) out.push_back(a.substr(start, comma - start));
      start = comma + 1;
    }
  }
  return out;
}

bool run_selected(const std::string& name, const std::vector<std::string>& patterns) {
  if (patterns.empty()) return true;
  for (const std::string& p : patterns)
    if (::fnmatch(p.c_str(), name.c_str(), 0) == 0) return true;
  return false;
}

}  // namespace adrsph::analysis
