// Every shipped case file parses and validates, and says what docs/benchmark.md says.
#include <gtest/gtest.h>

#include "adrsph/case.hpp"
#include "io_test_util.hpp"

namespace adrsph {
namespace {

std::filesystem::path case_file(const std::string& name) {
  return test::source_dir() / "cases" / name;
}

TEST(CaseFiles, EveryShippedCaseLoads) {
  int n = 0;
  for (const auto& e : std::filesystem::directory_iterator(test::source_dir() / "cases")) {
    if (e.path().extension() != ".toml") continue;
    // Study files (adrsph study) live beside the cases they use; test_study.cpp reads them.
    if (e.path().stem().string().ends_with("_study")) continue;
    SCOPED_TRACE(e.path().string());
    EXPECT_NO_THROW({
      const Case c = load_case(e.path());
      EXPECT_FALSE(c.name.empty());
    });
    ++n;
  }
  EXPECT_GE(n, 5);
}

TEST(CaseFiles, LfrIsThePapersReactor) {
  const Case c = load_case(case_file("lfr.toml"));
  EXPECT_EQ(c.name, "lfr");
  EXPECT_EQ(c.scheme, Scheme::modern);
  EXPECT_EQ(c.flow, Flow::wcsph);
  EXPECT_DOUBLE_EQ(c.geometry.length, 100.0);
  EXPECT_DOUBLE_EQ(c.geometry.half_width, 5.0);
  EXPECT_DOUBLE_EQ(c.particles.dx, 0.25);
  EXPECT_DOUBLE_EQ(c.fluid.rho0, 1.2);
  EXPECT_DOUBLE_EQ(c.fluid.nu, 15.0);
  EXPECT_DOUBLE_EQ(c.fluid.u_bulk, 100.0);
  EXPECT_DOUBLE_EQ(c.species.D, 10.0);
  EXPECT_DOUBLE_EQ(c.species.k, 1.462);
  EXPECT_DOUBLE_EQ(c.species.c_in, 2.0);
  EXPECT_DOUBLE_EQ(c.species.c_init, 2.0);
  EXPECT_DOUBLE_EQ(c.time.t_end, 10.0);
  EXPECT_NEAR(c.peclet(), 1000.0, 1e-9);
  EXPECT_EQ(c.source, case_file("lfr.toml"));
}

TEST(CaseFiles, PecletCases) {
  const std::pair<const char*, double> cases[] = {
      {"lfr_pe10.toml", 10.0}, {"lfr_pe1000.toml", 1000.0}, {"lfr_pe100000.toml", 100000.0}};
  for (const auto& [file, pe] : cases) {
    SCOPED_TRACE(file);
    const Case c = load_case(case_file(file));
    EXPECT_NEAR(c.peclet(), pe, 1e-9 * pe);
    EXPECT_DOUBLE_EQ(c.particles.dx, 0.25);
    EXPECT_DOUBLE_EQ(c.time.t_end, 10.0);
  }
}

TEST(CaseFiles, DefaultIsQuick) {
  const Case c = load_case(case_file("default.toml"));
  EXPECT_EQ(c.flow, Flow::prescribed);
  EXPECT_DOUBLE_EQ(c.particles.dx, 0.5);
  EXPECT_NEAR(c.peclet(), 1000.0, 1e-9);
  EXPECT_TRUE(c.time.stop_when_steady);
}

TEST(CaseFiles, NameDefaultsToFileStem) {
  test::TempDir dir;
  test::write_file(dir / "my_case.toml", "[species]\nD = 1.0\n");
  const Case c = load_case(dir / "my_case.toml");
  EXPECT_EQ(c.name, "my_case");
  EXPECT_DOUBLE_EQ(c.species.D, 1.0);
  EXPECT_DOUBLE_EQ(c.particles.dx, Case{}.particles.dx);  // everything else: defaults
}

// Every key has a default, but a file without any key is more likely the wrong file (or one
// not saved) than a wish for the default case: refused. One key is enough.
TEST(CaseFiles, EmptyFileIsRefusedAndOneKeyIsEnough) {
  test::TempDir dir;
  test::write_file(dir / "empty.toml", "# only a comment\n\n");
  EXPECT_THROW(load_case(dir / "empty.toml"), CaseError);
  test::write_file(dir / "one.toml", "name = \"one\"\n");
  EXPECT_NO_THROW(load_case(dir / "one.toml"));
}

TEST(CaseFiles, EveryKeyIsRead) {
  test::TempDir dir;
  test::write_file(dir / "all.toml", R"(name = "all"
scheme = "conventional"
flow = "prescribed"
[geometry]
length = 50
half_width = 2.5
[particles]
dx = 0.125
wall_layers = 4
inlet_layers = 6
outlet_layers = 5
skin = 0.2
[fluid]
rho0 = 1000.0
nu = 1.0
u_bulk = 10.0
c0_factor = 20.0
gamma = 1.0
background_pressure = 0.0
[species]
D = 0.5
k = 0.0
c_in = 1.0
c_init = 0.0
ale = false
[modern]
delta = 0.2
shift_eps = 0.25
shift_max = 0.1
[time]
t_end = 2.0
max_steps = 100
cfl = 0.5
viscous_number = 0.2
diffusion_number = 0.2
dt = 1e-4
check_interval = 0.1
stop_when_steady = false
steady_tol = 1e-3
steady_window = 0.2
average_window = 0.5
warm_start = true
[output]
field_times = [0.5, 1, 2]
progress = false
)");
  const Case c = load_case(dir / "all.toml");
  EXPECT_EQ(c.name, "all");
  EXPECT_EQ(c.scheme, Scheme::conventional);
  EXPECT_EQ(c.flow, Flow::prescribed);
  EXPECT_DOUBLE_EQ(c.geometry.length, 50.0);
  EXPECT_DOUBLE_EQ(c.geometry.half_width, 2.5);
  EXPECT_DOUBLE_EQ(c.particles.dx, 0.125);
  EXPECT_EQ(c.particles.wall_layers, 4);
  EXPECT_EQ(c.particles.inlet_layers, 6);
  EXPECT_EQ(c.particles.outlet_layers, 5);
  EXPECT_DOUBLE_EQ(c.particles.skin, 0.2);
  EXPECT_DOUBLE_EQ(c.fluid.rho0, 1000.0);
  EXPECT_DOUBLE_EQ(c.fluid.nu, 1.0);
  EXPECT_DOUBLE_EQ(c.fluid.u_bulk, 10.0);
  EXPECT_DOUBLE_EQ(c.fluid.c0_factor, 20.0);
  EXPECT_DOUBLE_EQ(c.fluid.gamma, 1.0);
  EXPECT_DOUBLE_EQ(c.fluid.background_pressure, 0.0);
  EXPECT_DOUBLE_EQ(c.species.D, 0.5);
  EXPECT_DOUBLE_EQ(c.species.k, 0.0);
  EXPECT_DOUBLE_EQ(c.species.c_in, 1.0);
  EXPECT_DOUBLE_EQ(c.species.c_init, 0.0);
  EXPECT_FALSE(c.species.ale);
  EXPECT_DOUBLE_EQ(c.modern.delta, 0.2);
  EXPECT_DOUBLE_EQ(c.modern.shift_eps, 0.25);
  EXPECT_DOUBLE_EQ(c.modern.shift_max, 0.1);
  EXPECT_DOUBLE_EQ(c.time.t_end, 2.0);
  EXPECT_EQ(c.time.max_steps, 100);
  EXPECT_DOUBLE_EQ(c.time.cfl, 0.5);
  EXPECT_DOUBLE_EQ(c.time.viscous_number, 0.2);
  EXPECT_DOUBLE_EQ(c.time.diffusion_number, 0.2);
  EXPECT_DOUBLE_EQ(c.time.dt, 1e-4);
  EXPECT_DOUBLE_EQ(c.time.check_interval, 0.1);
  EXPECT_FALSE(c.time.stop_when_steady);
  EXPECT_DOUBLE_EQ(c.time.steady_tol, 1e-3);
  EXPECT_DOUBLE_EQ(c.time.steady_window, 0.2);
  EXPECT_DOUBLE_EQ(c.time.average_window, 0.5);
  EXPECT_TRUE(c.time.warm_start);
  EXPECT_EQ(c.output.field_times, (std::vector<double>{0.5, 1.0, 2.0}));
  EXPECT_FALSE(c.output.progress);
}

TEST(CaseFiles, EnumNames) {
  EXPECT_STREQ(to_string(Scheme::modern), "modern");
  EXPECT_STREQ(to_string(Scheme::conventional), "conventional");
  EXPECT_STREQ(to_string(Flow::wcsph), "wcsph");
  EXPECT_STREQ(to_string(Flow::prescribed), "prescribed");
}

}  // namespace
}  // namespace adrsph
