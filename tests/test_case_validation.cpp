// Every validation rule: one case each, and the message names the key and the expected range.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "adrsph/case.hpp"
#include "io_test_util.hpp"

namespace adrsph {
namespace {

using ::testing::HasSubstr;

struct Rule {
  std::vector<std::string> sets;  // --set overrides on cases/lfr.toml
  std::string key;                // the key the message must name
  std::string expected;           // a piece of the expected range
};

void PrintTo(const Rule& r, std::ostream* os) {
  for (const auto& s : r.sets) *os << s << " ";
}

class Validation : public ::testing::TestWithParam<Rule> {};

TEST_P(Validation, RejectedWithKeyAndRange) {
  const Rule& r = GetParam();
  const auto file = test::source_dir() / "cases" / "lfr.toml";
  try {
    load_case(file, r.sets);
    FAIL() << "accepted";
  } catch (const CaseError& e) {
    EXPECT_EQ(e.key(), r.key) << e.what();
    EXPECT_THAT(e.what(), HasSubstr("'" + r.key + "'"));
    EXPECT_THAT(e.what(), HasSubstr(r.expected));
    EXPECT_EQ(e.file(), "--set") << "a bad value from --set is blamed on --set: " << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(
    Rules, Validation,
    ::testing::Values(
        Rule{{"name=\"\""}, "name", "1 to 200"}, Rule{{"name=a/b"}, "name", "letters"},
        Rule{{"geometry.length=0"}, "geometry.length", "> 0"},
        Rule{{"geometry.half_width=-5"}, "geometry.half_width", "> 0"},
        Rule{{"particles.dx=0"}, "particles.dx", "> 0"},
        Rule{{"particles.dx=0.3"}, "particles.dx", "geometry.length"},
        Rule{{"particles.dx=5"}, "particles.dx", "at least 4 particles across"},
        Rule{{"particles.wall_layers=2"}, "particles.wall_layers", "[3, 100]"},
        Rule{{"particles.wall_layers=101"}, "particles.wall_layers", "[3, 100]"},
        Rule{{"particles.inlet_layers=3"}, "particles.inlet_layers", "[4, 100]"},
        Rule{{"particles.inlet_layers=2000000000"}, "particles.inlet_layers", "[4, 100]"},
        Rule{{"particles.outlet_layers=2"}, "particles.outlet_layers", "[3, 100]"},
        Rule{{"particles.skin=-0.1"}, "particles.skin", "[0, 1]"},
        Rule{{"particles.jitter=0.5"}, "particles.jitter", "[0, 0.45]"},
        Rule{{"particles.wall_images=true", "particles.dx=2.5"},
             "particles.wall_images",
             "half_width > 3 dx"},
        Rule{{"time.dt_factor=-1"}, "time.dt_factor", "[0, 100]"},
        Rule{{"time.dt=1e-5", "time.dt_factor=2"}, "time.dt_factor", "time.dt is set"},
        Rule{{"fluid.rho0=0"}, "fluid.rho0", "> 0"}, Rule{{"fluid.nu=0"}, "fluid.nu", "> 0"},
        Rule{{"fluid.driving=body_force", "flow=prescribed"}, "fluid.driving", "\"pressure\""},
        Rule{{"fluid.driving=gravity"}, "fluid.driving", "\"body_force\""},
        Rule{{"fluid.u_bulk=-1"}, "fluid.u_bulk", "> 0"},
        Rule{{"fluid.c0_factor=0"}, "fluid.c0_factor", "> 0"},
        Rule{{"fluid.gamma=0.5"}, "fluid.gamma", "[1, 20]"},
        Rule{{"fluid.gamma=1e30"}, "fluid.gamma", "[1, 20]"},
        Rule{{"fluid.background_pressure=-0.01"}, "fluid.background_pressure", "[0, 10]"},
        Rule{{"fluid.background_pressure=11"}, "fluid.background_pressure", "[0, 10]"},
        Rule{{"fluid.rho0=1e308"}, "fluid.rho0", "pressure scale rho0 c0^2"},
        Rule{{"fluid.u_bulk=1e12"}, "fluid.u_bulk", "pressure scale rho0 c0^2"},
        Rule{{"fluid.c0_factor=1e30"}, "fluid.c0_factor", "pressure scale rho0 c0^2"},
        Rule{{"species.D=-1"}, "species.D", ">= 0"}, Rule{{"species.k=-1"}, "species.k", ">= 0"},
        Rule{{"species.c_in=-2"}, "species.c_in", "[0, 1e+20]"},
        Rule{{"species.c_in=1e308"}, "species.c_in", "[0, 1e+20]"},
        Rule{{"species.c_init=-2"}, "species.c_init", "[0, 1e+20]"},
        Rule{{"species.c_init=1e21"}, "species.c_init", "[0, 1e+20]"},
        Rule{{"scheme=conventional", "species.ale=true"}, "species.ale", "modern"},
        Rule{{"modern.delta=-0.1"}, "modern.delta", ">= 0"},
        Rule{{"modern.shift_eps=1.5"}, "modern.shift_eps", "[0, 1]"},
        Rule{{"modern.shift_max=-1"}, "modern.shift_max", "[0, 1]"},
        Rule{{"time.t_end=0"}, "time.t_end", "> 0"},
        Rule{{"time.max_steps=-1"}, "time.max_steps", ">= 0"},
        Rule{{"time.cfl=0"}, "time.cfl", "(0, 1]"}, Rule{{"time.cfl=1.5"}, "time.cfl", "(0, 1]"},
        Rule{{"time.viscous_number=0.3"}, "time.viscous_number", "(0, 0.25]"},
        Rule{{"time.diffusion_number=0"}, "time.diffusion_number", "(0, 0.25]"},
        Rule{{"time.diffusion_number=0.26"}, "time.diffusion_number", "(0, 0.25]"},
        Rule{{"time.dt=-1e-5"}, "time.dt", ">= 0"},
        Rule{{"time.check_interval=0"}, "time.check_interval", "> 0"},
        Rule{{"time.steady_tol=0"}, "time.steady_tol", "> 0"},
        Rule{{"time.steady_window=-1"}, "time.steady_window", ">= 0"},
        Rule{{"time.average_window=10"}, "time.average_window", "[0, 10)"},
        Rule{{"time.average_window=-1"}, "time.average_window", "[0, 10)"},
        Rule{{"output.field_times=[0]"}, "output.field_times[0]", "(0, 10]"},
        Rule{{"output.field_times=[1, 11]"}, "output.field_times[1]", "(0, 10]"},
        Rule{{"output.field_times=[2, 1]"}, "output.field_times[1]", "increasing"},
        Rule{{"output.outlet_interval=-0.01"}, "output.outlet_interval", ">= 0"},
        Rule{{"species.feed.shape=pulse", "time.stop_when_steady=false", "species.feed.width=0"},
             "species.feed.width",
             "> 0"},
        Rule{{"species.feed.shape=pulse", "species.feed.width=0.1", "time.stop_when_steady=true"},
             "time.stop_when_steady",
             "no steady state"},
        Rule{{"species.feed.shape=step", "time.warm_start=true"},
             "time.warm_start",
             "constant feed"},
        Rule{{"species.feed.shape=step", "species.feed.t0=-1"}, "species.feed.t0", "[0, 1e+20]"},
        Rule{
            {"species.feed.shape=step", "species.feed.base=-1"}, "species.feed.base", "[0, 1e+20]"},
        Rule{{"species.feed.shape=table", "time.stop_when_steady=false",
              "species.feed.table=[[0, 1]]"},
             "species.feed.table",
             "at least two"},
        Rule{{"species.feed.shape=table", "time.stop_when_steady=false",
              "species.feed.table=[[0, 1], [0, 2]]"},
             "species.feed.table[1][0]",
             "increasing"},
        Rule{{"species.feed.shape=table", "time.stop_when_steady=false",
              "species.feed.table=[[0, 1], [1, -2]]"},
             "species.feed.table[1][1]",
             "[0, 1e+20]"},
        Rule{{"species.feed.table=[[0, 1], [1]]"}, "species.feed.table[1]", "a pair"},
        Rule{{"species.feed.shape=square"}, "species.feed.shape", "\"pulse\""}));

TEST(ValidationDetail, WidthNotAMultipleOfDx) {
  // 100 / 0.25 fits the length, 2 * 5.1 / 0.25 = 40.8 does not fit the width.
  try {
    load_case(test::source_dir() / "cases" / "lfr.toml", {"geometry.half_width=5.1"});
    FAIL() << "accepted";
  } catch (const CaseError& e) {
    EXPECT_EQ(e.key(), "particles.dx");
    EXPECT_THAT(e.what(), HasSubstr("2*half_width"));
  }
}

TEST(ValidationDetail, BadValueInTheFileIsBlamedOnTheFile) {
  test::TempDir dir;
  test::write_file(dir / "neg.toml", "[species]\nD = -1.0\n");
  try {
    load_case(dir / "neg.toml");
    FAIL() << "accepted";
  } catch (const CaseError& e) {
    EXPECT_EQ(e.file(), (dir / "neg.toml").string());
    EXPECT_THAT(e.what(), HasSubstr("'species.D'"));
    EXPECT_THAT(e.what(), HasSubstr("got -1"));
  }
}

TEST(ValidationDetail, DefaultCaseIsValid) {
  Case c;
  c.name = std::string("x");  // (from a literal: GCC 12 -Wrestrict false positive)
  EXPECT_NO_THROW(validate_case(c));
}

TEST(ValidationDetail, CaseBuiltInCode) {
  Case c;
  c.name = std::string("x");  // (from a literal: GCC 12 -Wrestrict false positive)
  c.species.D = -1.0;
  try {
    validate_case(c);
    FAIL() << "accepted";
  } catch (const CaseError& e) {
    EXPECT_EQ(e.key(), "species.D");
    EXPECT_THAT(e.what(), HasSubstr("<case>"));
  }
}

TEST(ValidationDetail, NanIsRejected) {
  Case c;
  c.name = std::string("x");  // (from a literal: GCC 12 -Wrestrict false positive)
  c.fluid.nu = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(validate_case(c), CaseError);
}

TEST(ValidationDetail, ZeroDiffusionIsAllowed) {
  EXPECT_NO_THROW(load_case(test::source_dir() / "cases" / "lfr.toml", {"species.D=0"}));
}

}  // namespace
}  // namespace adrsph
