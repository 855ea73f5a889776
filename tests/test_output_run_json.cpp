// run.json from a synthetic result: every documented key, its value and its type.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "adrsph/io/run_json.hpp"
#include "io_test_util.hpp"

namespace adrsph {
namespace {

RunResult sample_result() {
  RunResult r;
  r.t_reached = 4.5;
  r.steps = 1234;
  r.wall_s = 12.5;
  r.n_particles = 5000;
  r.n_fluid = 4000;
  r.particle_steps_per_s = 4.9e5;
  r.dt = {1e-4, 2e-4, 3e-3, 5e-3, 1e-4, "acoustic"};
  r.steady = true;
  r.t_steady = 4.25;
  r.phase_seconds = {{"neighbours", 3.0}, {"forces", 7.5}};
  r.stations = {{25.0, 50.0, 100.0}, {1.38, 1.04, 0.63}};
  r.average_window = 0.5;
  r.probe_interpolation = "Shepard";
  r.engine_bytes = {1000, 2000, 300, 400};
  r.balance_flow_rate = 1333.0;
  r.species_balance = {{"C", 0.05, 0.049, 0.0, 0.001}};
  return r;
}

Case sample_case() {
  Case c;
  c.name = "sample";
  c.source = "cases/sample.toml";
  c.scheme = Scheme::conventional;
  c.flow = Flow::prescribed;
  c.particles.dx = 0.5;
  return c;
}

TEST(RunJson, EveryKey) {
  const auto j = nlohmann::json::parse(
      run_json_text(sample_case(), sample_result(), {2, 13.0, 3, {"species.D=1"}, 0.5, 0.75}));
  for (const char* key : test::kRunJsonKeys) EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["case"], "sample");
  EXPECT_EQ(j["case_file"], "cases/sample.toml");
  EXPECT_EQ(j["scheme"], "conventional");
  EXPECT_EQ(j["flow"], "prescribed");
  EXPECT_DOUBLE_EQ(j["Pe"].get<double>(), 1000.0);
  EXPECT_DOUBLE_EQ(j["D"].get<double>(), 10.0);
  EXPECT_DOUBLE_EQ(j["k"].get<double>(), 1.462);
  EXPECT_DOUBLE_EQ(j["dx"].get<double>(), 0.5);
  EXPECT_EQ(j["particles"], 5000);
  EXPECT_EQ(j["fluid_particles"], 4000);
  EXPECT_EQ(j["threads"], 2);
  EXPECT_EQ(j["overrides"], nlohmann::json::array({"species.D=1"}));
  EXPECT_DOUBLE_EQ(j["species_balance"]["flow_rate"].get<double>(), 1333.0);
  EXPECT_DOUBLE_EQ(j["species_balance"]["C"]["inflow"].get<double>(), 0.05);
  EXPECT_DOUBLE_EQ(j["species_balance"]["C"]["outflow"].get<double>(), 0.049);
  EXPECT_DOUBLE_EQ(j["species_balance"]["C"]["held"].get<double>(), 0.001);
  EXPECT_EQ(j["wall_images"], false);
  EXPECT_DOUBLE_EQ(j["load_average"]["start"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(j["load_average"]["end"].get<double>(), 0.75);
  EXPECT_DOUBLE_EQ(j["t_end"].get<double>(), 10.0);
  EXPECT_DOUBLE_EQ(j["t_reached"].get<double>(), 4.5);
  EXPECT_EQ(j["steps"], 1234);
  EXPECT_DOUBLE_EQ(j["wall_seconds"].get<double>(), 12.5);  // the simulation's own timing
  EXPECT_DOUBLE_EQ(j["particle_steps_per_second"].get<double>(), 4.9e5);
  EXPECT_DOUBLE_EQ(j["dt"]["chosen"].get<double>(), 1e-4);
  EXPECT_EQ(j["dt"]["binding"], "acoustic");
  EXPECT_DOUBLE_EQ(j["dt"]["acoustic"].get<double>(), 1e-4);
  EXPECT_DOUBLE_EQ(j["dt"]["advective"].get<double>(), 2e-4);
  EXPECT_DOUBLE_EQ(j["dt"]["viscous"].get<double>(), 3e-3);
  EXPECT_DOUBLE_EQ(j["dt"]["diffusion"].get<double>(), 5e-3);
  EXPECT_EQ(j["steady"], true);
  EXPECT_DOUBLE_EQ(j["t_steady"].get<double>(), 4.25);
  EXPECT_EQ(j["lost_particles"], 0);
  EXPECT_EQ(j["status"], "ok");
  EXPECT_EQ(j["message"], "");
  EXPECT_TRUE(j["failure"].is_null());
  EXPECT_EQ(j["probe_interpolation"], "Shepard");
  EXPECT_DOUBLE_EQ(j["average_window"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(j["phase_seconds"]["neighbours"].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(j["phase_seconds"]["forces"].get<double>(), 7.5);
  EXPECT_DOUBLE_EQ(j["stations"]["25"].get<double>(), 1.38);
  EXPECT_DOUBLE_EQ(j["stations"]["50"].get<double>(), 1.04);
  EXPECT_DOUBLE_EQ(j["stations"]["100"].get<double>(), 0.63);
  EXPECT_EQ(j["field_frames"], 3);
  EXPECT_TRUE(j["warm_start"].is_null());
  EXPECT_EQ(j["engine_bytes"]["particles"], 1000);
  EXPECT_EQ(j["engine_bytes"]["neighbour_lists"], 2000);
  EXPECT_EQ(j["engine_bytes"]["diffusion_weights"], 300);
  EXPECT_EQ(j["engine_bytes"]["pair_records"], 400);
}

TEST(RunJson, WarmStart) {
  RunResult r = sample_result();
  r.warm_started = true;
  r.warm_start_t = 3.5;
  r.warm_start_steps = 5600;
  r.warm_start_steady = true;
  r.warm_start_wall_s = 20.0;
  const auto j = nlohmann::json::parse(run_json_text(sample_case(), r, {}));
  EXPECT_EQ(j["warm_start"]["flow"], "prescribed");
  EXPECT_DOUBLE_EQ(j["warm_start"]["t_reached"].get<double>(), 3.5);
  EXPECT_EQ(j["warm_start"]["steps"], 5600);
  EXPECT_EQ(j["warm_start"]["steady"], true);
  EXPECT_DOUBLE_EQ(j["warm_start"]["wall_seconds"].get<double>(), 20.0);
}

TEST(RunJson, NotSteadyAndFailed) {
  RunResult r = sample_result();
  r.steady = false;
  r.status = "failed";
  r.message = "non-finite density at t = 0.1 s";
  r.failure = {"density", 0.1, 42, 12.5, std::nan(""), 0.3};
  r.wall_s = 0.0;
  r.lost_particles = 7;
  r.stations.c_mean[1] = std::nan("");
  const auto j =
      nlohmann::json::parse(run_json_text(sample_case(), r, {1, 13.0, 0, {}, -1.0, -1.0}));
  EXPECT_TRUE(j["t_steady"].is_null());
  EXPECT_TRUE(j["load_average"]["start"].is_null());
  EXPECT_EQ(j["steady"], false);
  EXPECT_EQ(j["status"], "failed");
  EXPECT_EQ(j["message"], "non-finite density at t = 0.1 s");
  EXPECT_EQ(j["failure"]["kind"], "density");
  EXPECT_EQ(j["failure"]["step"], 42);
  EXPECT_DOUBLE_EQ(j["failure"]["x"].get<double>(), 12.5);
  EXPECT_TRUE(j["failure"]["y"].is_null());
  EXPECT_DOUBLE_EQ(j["wall_seconds"].get<double>(), 13.0);  // the CLI's timing as fallback
  EXPECT_EQ(j["lost_particles"], 7);
  EXPECT_TRUE(j["stations"]["50"].is_null());  // JSON has no NaN
}

TEST(RunJson, InfinitePecletIsNull) {
  Case c = sample_case();
  c.species.D = 0.0;
  const auto j = nlohmann::json::parse(run_json_text(c, sample_result(), {}));
  EXPECT_TRUE(j["Pe"].is_null());
}

TEST(RunJson, WritesTheFile) {
  test::TempDir dir;
  write_run_json(dir / "run.json", sample_case(), sample_result(), {});
  const auto j = nlohmann::json::parse(test::read_file(dir / "run.json"));
  EXPECT_EQ(j["case"], "sample");
  EXPECT_THROW(write_run_json(dir / "nodir" / "run.json", sample_case(), sample_result(), {}),
               std::runtime_error);
}

}  // namespace

// The binary names itself: the release CMake declares and the commit it was built from
// (cmake/build_info.cmake), so that a result in a report can be traced to its code.
TEST(RunJson, NamesTheBuild) {
  const auto j = nlohmann::json::parse(run_json_text(sample_case(), sample_result(), {}));
  EXPECT_EQ(j["version"], ADRSPH_PROJECT_VERSION);
  ASSERT_TRUE(j["commit"].is_string());
  const std::string commit = j["commit"].get<std::string>();
  // 12 lower-case hex digits, optionally followed by "-dirty" (std::regex is avoided: GCC 12
  // warns maybe-uninitialized inside <regex> at -O2, which -Werror turns into a build failure).
  const std::string_view hash = std::string_view(commit).substr(0, 12);
  const std::string_view rest = std::string_view(commit).substr(hash.size());
  const bool hex = hash.size() == 12 && std::all_of(hash.begin(), hash.end(), [](char c) {
                     return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
                   });
  EXPECT_TRUE(commit == "unknown" || (hex && (rest.empty() || rest == "-dirty"))) << commit;
}

}  // namespace adrsph
