// DIR/run.json of a transient reference (docs/reference.md, "Transient mode", and "A network
// in time"). `adrsph rtd` reads it as it reads a run's: "status" and the "overrides" to apply
// to DIR/case.toml.
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "adrsph/reference_network_transient.hpp"
#include "adrsph/reference_transient.hpp"

namespace adrsph::reference {
namespace {

using Json = nlohmann::ordered_json;

Json number(double v) {
  return std::isfinite(v) ? Json(v) : Json(nullptr);
}

// What was solved: the case, the overrides, the solver and the grid.
Json head(const Case& c, const std::vector<std::string>& overrides, const TransientReport& r,
          const Grid& g) {
  Json j;
  j["case"] = c.name;
  j["case_file"] = c.source.string();
  j["status"] = r.converged ? "ok" : "failed";  // failed: a step missed its tolerance
  j["overrides"] = overrides;
  j["transient"] = true;
  j["solver"] = r.solver;
  j["grid"] = Json{{"nx", g.nx}, {"ny", g.ny}};
  return j;
}

// How the steps went.
void add_steps(Json& j, const Case& c, const TransientReport& r, double t_reached) {
  j["dt"] = r.dt;
  j["steps"] = r.steps;
  j["t_end"] = c.time.t_end;
  j["t_reached"] = t_reached;
  j["outlet_interval"] = c.output.outlet_interval;
  j["started_at_rest"] = r.started_at_rest;
  j["corrections"] = r.corrections;
  j["max_step_corrections"] = r.max_step_corrections;
  j["worst_change"] = number(r.worst_change);
  j["converged"] = r.converged;
}

Json amounts(const TransientBalance& b) {
  return Json{{"flow_rate", number(b.flow_rate)},       {"inflow", number(b.inflow)},
              {"outflow", number(b.outflow)},           {"reacted", number(b.reacted)},
              {"held_initial", number(b.held_initial)}, {"held_final", number(b.held_final)}};
}

void add_times(Json& j, const TransientReport& r, double wall_seconds) {
  j["assembly_seconds"] = number(r.assembly_seconds);
  j["factor_seconds"] = number(r.factor_seconds);
  j["step_seconds"] = number(r.step_seconds);
  j["wall_seconds"] = number(wall_seconds);
}

void write_json(const std::filesystem::path& file, const Json& j) {
  std::ofstream out(file, std::ios::binary);
  if (!out) throw std::runtime_error(file.string() + ": cannot open for writing");
  out << j.dump(2) << "\n";
  if (!out) throw std::runtime_error(file.string() + ": write failed");
}

}  // namespace

void write_transient_run_json(const std::filesystem::path& file, const Case& c,
                              const std::vector<std::string>& overrides, const TransientSolution& s,
                              double wall_seconds) {
  Json j = head(c, overrides, s.report, s.final.grid);
  j["Pe"] = number(c.peclet());
  j["D"] = c.species.D;
  j["k"] = c.species.k;
  add_steps(j, c, s.report, s.t_reached);
  Json balance = Json{{"unit", "amount per flow rate, mol/m^3 s"}};
  balance.update(amounts(s.balance));
  j["balance"] = balance;
  add_times(j, s.report, wall_seconds);
  write_json(file, j);
}

void write_network_transient_run_json(const std::filesystem::path& file, const Case& c,
                                      const std::vector<std::string>& overrides,
                                      const NetworkTransientSolution& s, double wall_seconds) {
  Json j = head(c, overrides, s.report, s.final.grid);
  j["network"] = true;
  Json names = Json::array();
  for (int k = 0; k < c.species_count(); ++k) names.push_back(c.species_at(k).name);
  j["species"] = names;
  add_steps(j, c, s.report, s.t_reached);
  j["factorisations"] = s.factorisations;
  j["coupled_steps"] = s.coupled_steps;
  Json balance = Json{{"unit", "amount per flow rate, mol/m^3 s; reacted = net consumption"}};
  for (std::size_t k = 0; k < s.balance.size(); ++k)
    balance[c.species_at(static_cast<int>(k)).name] = amounts(s.balance[k]);
  j["balance"] = balance;
  add_times(j, s.report, wall_seconds);
  write_json(file, j);
}

}  // namespace adrsph::reference
