// DIR/run.json of a transient reference (docs/reference.md, "Transient mode"). `adrsph rtd`
// reads it as it reads a run's: "status" and the "overrides" to apply to DIR/case.toml.
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "adrsph/reference_transient.hpp"

namespace adrsph::reference {
namespace {

using Json = nlohmann::ordered_json;

Json number(double v) {
  return std::isfinite(v) ? Json(v) : Json(nullptr);
}

}  // namespace

void write_transient_run_json(const std::filesystem::path& file, const Case& c,
                              const std::vector<std::string>& overrides, const TransientSolution& s,
                              double wall_seconds) {
  const TransientReport& r = s.report;
  const TransientBalance& b = s.balance;
  Json j;
  j["case"] = c.name;
  j["case_file"] = c.source.string();
  j["status"] = r.converged ? "ok" : "failed";  // failed: a step missed its tolerance
  j["overrides"] = overrides;
  j["transient"] = true;
  j["solver"] = r.solver;
  j["grid"] = Json{{"nx", s.final.grid.nx}, {"ny", s.final.grid.ny}};
  j["Pe"] = number(c.peclet());
  j["D"] = c.species.D;
  j["k"] = c.species.k;
  j["dt"] = r.dt;
  j["steps"] = r.steps;
  j["t_end"] = c.time.t_end;
  j["t_reached"] = s.t_reached;
  j["outlet_interval"] = c.output.outlet_interval;
  j["started_at_rest"] = r.started_at_rest;
  j["corrections"] = r.corrections;
  j["max_step_corrections"] = r.max_step_corrections;
  j["worst_change"] = number(r.worst_change);
  j["converged"] = r.converged;
  j["balance"] = Json{{"unit", "amount per flow rate, mol/m^3 s"},
                      {"flow_rate", number(b.flow_rate)},
                      {"inflow", number(b.inflow)},
                      {"outflow", number(b.outflow)},
                      {"reacted", number(b.reacted)},
                      {"held_initial", number(b.held_initial)},
                      {"held_final", number(b.held_final)}};
  j["assembly_seconds"] = number(r.assembly_seconds);
  j["factor_seconds"] = number(r.factor_seconds);
  j["step_seconds"] = number(r.step_seconds);
  j["wall_seconds"] = number(wall_seconds);
  std::ofstream out(file, std::ios::binary);
  if (!out) throw std::runtime_error(file.string() + ": cannot open for writing");
  out << j.dump(2) << "\n";
  if (!out) throw std::runtime_error(file.string() + ": write failed");
}

}  // namespace adrsph::reference
