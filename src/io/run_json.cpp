// run.json writer (nlohmann::ordered_json keeps the documented key order).
#include "adrsph/io/run_json.hpp"

#include "io/build_info.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

namespace adrsph {
namespace {

using Json = nlohmann::ordered_json;

// Non-finite numbers become null (JSON has no NaN).
Json number(double v) {
  return std::isfinite(v) ? Json(v) : Json(nullptr);
}

// "25", "50", "100", "12.5": the station abscissa as an object key.
std::string x_key(double x) {
  std::ostringstream os;
  os.precision(10);
  os << x;
  return os.str();
}

}  // namespace

std::string run_json_text(const Case& c, const RunResult& r, const RunContext& ctx) {
  Json j;
  j["case"] = c.name;
  j["case_file"] = c.source.string();
  j["scheme"] = to_string(c.scheme);
  j["flow"] = to_string(c.flow);
  j["Pe"] = number(c.peclet());
  j["D"] = c.species.D;
  j["k"] = c.species.k;
  // The [[reaction]] tables (empty: species.k alone).
  j["reactions"] = Json::array();
  for (const Reaction& r : c.reactions) {
    Json zones = Json::array();
    for (const Reaction::Zone& z : r.zones) zones.push_back({z.x0, z.x1, z.y0, z.y1, z.factor});
    Json reactants = Json::array(), products = Json::array();
    for (const int s : r.reactants) reactants.push_back(c.species_at(s).name);
    for (const int s : r.products) products.push_back(c.species_at(s).name);
    j["reactions"].push_back({{"law", to_string(r.law)},
                              {"k", r.k},
                              {"order", r.order},
                              {"km", r.km},
                              {"zones", zones},
                              {"reactants", reactants},
                              {"products", products}});
  }
  // Every species (the first is the one of D, k, probes.csv and stations.csv).
  j["species"] = Json::array();
  for (int s = 0; s < c.species_count(); ++s) {
    const Case::Species& sp = c.species_at(s);
    j["species"].push_back(
        {{"name", sp.name}, {"D", sp.D}, {"c_in", sp.c_in}, {"c_init", sp.c_init}});
  }
  j["dx"] = c.particles.dx;
  j["particles"] = r.n_particles;
  j["fluid_particles"] = r.n_fluid;
  j["threads"] = ctx.threads;
  j["t_end"] = c.time.t_end;
  j["t_reached"] = number(r.t_reached);
  j["steps"] = r.steps;
  j["wall_seconds"] = number(r.wall_s > 0.0 ? r.wall_s : ctx.wall_seconds);
  j["particle_steps_per_second"] = number(r.particle_steps_per_s);
  j["list_rebuilds"] = r.list_rebuilds;
  j["list_two_pass_builds"] = r.list_two_pass_builds;
  j["mean_neighbours"] = number(r.mean_neighbours);
  j["dt"] = Json{{"chosen", number(r.dt.chosen)},
                 {"binding", r.dt.binding},
                 {"acoustic", number(r.dt.acoustic)},
                 {"advective", number(r.dt.advective)},
                 {"viscous", number(r.dt.viscous)},
                 {"diffusion", number(r.dt.diffusion)},
                 {"diffusion_stages", r.dt.diffusion_stages}};
  j["steady"] = r.steady;
  j["t_steady"] = r.steady ? number(r.t_steady) : Json(nullptr);
  j["lost_particles"] = r.lost_particles;
  j["status"] = r.status;
  j["message"] = r.message;
  j["failure"] = r.status == "failed"
                     ? Json{{"kind", r.failure.kind},   {"t", number(r.failure.t)},
                            {"step", r.failure.step},   {"x", number(r.failure.x)},
                            {"y", number(r.failure.y)}, {"value", number(r.failure.value)}}
                     : Json(nullptr);
  j["probe_interpolation"] = r.probe_interpolation;
  j["average_window"] = r.average_window;
  j["warm_start"] = r.warm_started ? Json{{"flow", "prescribed"},
                                          {"t_reached", number(r.warm_start_t)},
                                          {"steps", r.warm_start_steps},
                                          {"steady", r.warm_start_steady},
                                          {"wall_seconds", number(r.warm_start_wall_s)}}
                                   : Json(nullptr);
  Json phases = Json::object();
  for (const auto& [name, s] : r.phase_seconds) phases[name] = number(s);
  j["phase_seconds"] = phases;
  Json stations = Json::object();
  for (std::size_t i = 0; i < r.stations.x_mm.size() && i < r.stations.c_mean.size(); ++i)
    stations[x_key(r.stations.x_mm[i])] = number(r.stations.c_mean[i]);
  j["stations"] = stations;
  // The section averages at the stations of the other species of a network, by name.
  if (!r.more_species.empty()) {
    Json more = Json::object();
    for (const RunResult::SpeciesProbes& sp : r.more_species) {
      Json st = Json::object();
      for (std::size_t i = 0; i < sp.stations.x_mm.size(); ++i)
        st[x_key(sp.stations.x_mm[i])] = number(sp.stations.c_mean[i]);
      more[sp.name] = st;
    }
    j["species_stations"] = more;
  }
  // Each species' ledger over the nominal flow rate (simulation.hpp, RunResult).
  Json balance = Json::object();
  balance["unit"] = "amount per nominal flow rate, mol/m^3 s";
  balance["flow_rate"] = number(r.balance_flow_rate);
  for (const RunResult::SpeciesBalance& b : r.species_balance)
    balance[b.name.empty() ? "species" : b.name] = Json{{"inflow", number(b.inflow)},
                                                        {"outflow", number(b.outflow)},
                                                        {"reacted", number(b.reacted)},
                                                        {"held", number(b.held)}};
  j["species_balance"] = balance;
  j["field_frames"] = ctx.field_frames;
  j["overrides"] = ctx.overrides;
  // Wall times mean little without the machine's load: a busy machine slows a run.
  j["load_average"] = Json{{"start", ctx.load_start >= 0 ? Json(ctx.load_start) : Json(nullptr)},
                           {"end", ctx.load_end >= 0 ? Json(ctx.load_end) : Json(nullptr)}};
  j["ale"] = c.species.ale;
  j["wall_images"] = c.particles.wall_images;
  j["driving"] = c.fluid.driving == Driving::body_force ? "body_force" : "pressure";
  j["peak_rss_bytes"] = number(r.peak_rss_bytes);
  j["engine_bytes"] = {{"particles", r.engine_bytes.particles},
                       {"neighbour_lists", r.engine_bytes.neighbour_lists},
                       {"diffusion_weights", r.engine_bytes.diffusion_weights},
                       {"pair_records", r.engine_bytes.pair_records}};
  j["restarts"] = r.restarts;
  j["steady_criterion"] = Json{{"tol", number(r.steady_criterion.tol)},
                               {"window", number(r.steady_criterion.window)},
                               {"t_min", number(r.steady_criterion.t_min)}};
  j["version"] = build_version();
  j["commit"] = build_commit();
  j["results_version"] = kResultsVersion;
  return j.dump(2) + "\n";
}

void write_run_json(const std::filesystem::path& file, const Case& c, const RunResult& r,
                    const RunContext& ctx) {
  const std::string text = run_json_text(c, r, ctx);
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();
  if (!out) throw std::runtime_error(file.string() + ": cannot write run.json");
}

}  // namespace adrsph
