// Hostile input (docs/robustness.md): malformed case files, bad --set values, odd options and
// paths, files that `compare` cannot read. Each must end at start-up with exit 2 (bad input) and
// one line that names the problem: never a crash, a hang, a run that starts anyway, or a file
// written. The built binary is run under `timeout`, so a hang fails the test instead of
// stopping the suite.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "boundaries/channel_scene.hpp"
#include "io_test_util.hpp"

namespace adrsph {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

struct Hostile {
  const char* name;
  std::map<std::string, std::string> files;  // written into the test directory first
  std::string args;                          // after `adrsph`; {lfr} is the shipped case
  std::vector<std::string> says;             // substrings of the error line
  int exit_code = 2;
};

void PrintTo(const Hostile& h, std::ostream* os) {
  *os << h.name;
}

std::string lfr() {
  std::string s(1, '\'');
  s += (test::source_dir() / "cases" / "lfr.toml").string();
  s += '\'';
  return s;
}

std::string expand(std::string args) {
  for (std::size_t at; (at = args.find("{lfr}")) != std::string::npos;) args.replace(at, 5, lfr());
  return args;
}

// Every path under `dir`, relative, with the size of the files.
std::set<std::string> listing(const fs::path& dir) {
  std::set<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    std::string entry = fs::relative(e.path(), dir).string();
    if (e.is_regular_file()) {
      entry += ' ';
      entry += std::to_string(e.file_size());
    }
    out.insert(entry);
  }
  return out;
}

// a + b by appending (GCC 12's -Wrestrict misfires on string + string chains).
std::string with(std::string a, const std::string& b) {
  a += b;
  return a;
}

std::string binary_garbage() {
  std::string s;
  unsigned state = 12345;
  for (int i = 0; i < 4096; ++i) {
    state = state * 1103515245u + 12345u;
    s.push_back(static_cast<char>(state >> 16));
  }
  return s;
}

class HostileInput : public ::testing::TestWithParam<Hostile> {};

TEST_P(HostileInput, RefusedAtStartWithOneLine) {
  const Hostile& h = GetParam();
  test::TempDir dir;
  for (const auto& [name, text] : h.files) {
    fs::create_directories((dir / name).parent_path());
    test::write_file(dir / name, text);
  }
  // An earlier run's output that a refused start must leave as it was.
  fs::create_directories(dir / "old");
  test::write_file(dir / "old" / "run.json", "{\"old\": true}\n");
  const auto before = listing(dir.path());

  std::string command = "timeout 60 '";
  command += ADRSPH_BINARY;
  command += "' ";
  command += expand(h.args);
  const auto r = test::run_shell(command, dir.path());
  EXPECT_EQ(r.exit_code, h.exit_code) << r.err << r.out;
  EXPECT_EQ(r.out, "");
  // One line naming the problem; CLI11's own errors add the line "Run with --help ...".
  const std::string& err = r.err;
  const std::string first = err.substr(0, err.find('\n'));
  for (const auto& s : h.says) EXPECT_THAT(first, HasSubstr(s)) << err;
  const auto lines = std::count(err.begin(), err.end(), '\n');
  EXPECT_TRUE(lines == 1 || (lines == 2 && err.find("Run with --help") != std::string::npos))
      << err;
  for (const char* crash : {"terminate", "Segmentation", "Aborted", "std::", "what()"})
    EXPECT_EQ(err.find(crash), std::string::npos) << err;
  // Nothing written: no output directory, no DIR.partial, the old output intact.
  EXPECT_EQ(listing(dir.path()), before);
}

// The shipped case at the coarse spacing, so that a run that wrongly starts is cheap.
const std::string kRun = "run {lfr} --set particles.dx=0.5 --set time.max_steps=2 --out old";
const std::string kGood = "name = \"x\"\n";

INSTANTIATE_TEST_SUITE_P(
    Cases, HostileInput,
    ::testing::Values(
        // The case file itself.
        Hostile{"MissingFile", {}, "run nothing.toml --out old", {"nothing.toml"}},
        Hostile{"EmptyFile", {{"e.toml", ""}}, "run e.toml --out old", {"e.toml", "no keys"}},
        Hostile{"DirectoryAsCase", {}, "run . --out old", {"."}},
        Hostile{"BinaryGarbage",
                {{"g.toml", binary_garbage()}},
                "run g.toml --out old",
                {"g.toml", "syntax"}},
        Hostile{"NulByte",
                {{"n.toml", std::string("name = \"a\0b\"\n", 13)}},
                "run n.toml --out old",
                {"n.toml:1"}},
        Hostile{
            "UnclosedString", {{"s.toml", "name = \"x\n"}}, "run s.toml --out old", {"s.toml:1"}},
        Hostile{"DuplicateKey",
                {{"d.toml", "name = \"a\"\nname = \"b\"\n"}},
                "run d.toml --out old",
                {"d.toml:2", "name"}},
        Hostile{"DuplicateTable",
                {{"t.toml", "[species]\nD = 1\n[species]\nk = 1\n"}},
                "run t.toml --out old",
                {"t.toml:3", "species"}},
        Hostile{"DeepNesting",
                {{"deep.toml", with("a = ", std::string(100000, '['))}},
                "run deep.toml --out old",
                {"deep.toml:1"}},
        Hostile{"UnknownKey",
                {{"u.toml", with(kGood, "[species]\nDD = 1\n")}},
                "run u.toml --out old",
                {"species.DD", "species.D"}},
        Hostile{"MisspeltTable",
                {{"m.toml", with(kGood, "[speceis]\nD = 1\n")}},
                "run m.toml --out old",
                {"speceis"}},
        Hostile{"StringForNumber",
                {{"w.toml", with(kGood, "[particles]\ndx = \"0.5\"\n")}},
                "run w.toml --out old",
                {"particles.dx", "number"}},
        Hostile{"TableForNumber",
                {{"w.toml", with(kGood, "[species]\nD = { a = 1 }\n")}},
                "run w.toml --out old",
                {"species.D"}},
        Hostile{"ArrayForNumber",
                {{"w.toml", with(kGood, "[species]\nk = [1, 2]\n")}},
                "run w.toml --out old",
                {"species.k"}},
        Hostile{"BoolForNumber",
                {{"w.toml", with(kGood, "[fluid]\nnu = true\n")}},
                "run w.toml --out old",
                {"fluid.nu"}},
        Hostile{"UnknownScheme",
                {{"w.toml", with(kGood, "scheme = \"modrn\"\n")}},
                "run w.toml --out old",
                {"scheme", "modern"}},
        Hostile{"NumberForName", {{"w.toml", "name = 3\n"}}, "run w.toml --out old", {"name"}},
        Hostile{"HugeName",
                {{"w.toml", with(with("name = \"", std::string(100000, 'x')), "\"\n")}},
                "run w.toml",
                {"name", "1 to 200"}},
        // --set.
        Hostile{"SetWithoutValue", {}, with(kRun, " --set particles.dx"), {"key=value"}},
        Hostile{"SetWithoutKey", {}, with(kRun, " --set =3"), {"key=value"}},
        Hostile{"SetUnknownKey", {}, with(kRun, " --set species.DD=1"), {"species.DD"}},
        Hostile{"SetWordForNumber", {}, with(kRun, " --set fluid.nu=abc"), {"fluid.nu", "number"}},
        Hostile{"SetNan", {}, with(kRun, " --set species.D=nan"), {"species.D"}},
        Hostile{"SetInf", {}, with(kRun, " --set species.k=inf"), {"species.k"}},
        Hostile{"SetNegativeRho", {}, with(kRun, " --set fluid.rho0=-1"), {"fluid.rho0"}},
        Hostile{"SetZeroViscosity", {}, with(kRun, " --set fluid.nu=0"), {"fluid.nu"}},
        Hostile{"SetZeroSpeed", {}, with(kRun, " --set fluid.u_bulk=0"), {"fluid.u_bulk"}},
        Hostile{"SetZeroLength", {}, with(kRun, " --set geometry.length=0"), {"geometry.length"}},
        Hostile{"SetNegativeWidth",
                {},
                with(kRun, " --set geometry.half_width=-5"),
                {"geometry.half_width"}},
        Hostile{"SetZeroDx", {}, with(kRun, " --set particles.dx=0"), {"particles.dx"}},
        Hostile{"SetDxNotDividing", {}, with(kRun, " --set particles.dx=0.3"), {"particles.dx"}},
        Hostile{"SetHugeConcentration",
                {},
                with(kRun, " --set species.c_in=1e308"),
                {"species.c_in", "1e+20"}},
        Hostile{
            "SetNegativeInitial", {}, with(kRun, " --set species.c_init=-1"), {"species.c_init"}},
        Hostile{"SetHugeDensity",
                {},
                with(kRun, " --set fluid.rho0=1e308"),
                {"fluid.rho0", "rho0 c0^2"}},
        Hostile{"SetHugeSpeed", {}, with(kRun, " --set fluid.u_bulk=1e30"), {"fluid.u_bulk"}},
        Hostile{"SetHugeGamma", {}, with(kRun, " --set fluid.gamma=1e30"), {"fluid.gamma"}},
        Hostile{"SetHugeBackgroundPressure",
                {},
                with(kRun, " --set fluid.background_pressure=1e30"),
                {"fluid.background_pressure"}},
        Hostile{"SetHugeLayers",
                {},
                with(kRun, " --set particles.inlet_layers=2000000000"),
                {"particles.inlet_layers"}},
        Hostile{"SetZeroEndTime", {}, with(kRun, " --set time.t_end=0"), {"time.t_end"}},
        Hostile{"SetHugeFieldTime",
                {},
                with(kRun, " --set output.field_times=[1e308]"),
                {"output.field_times[0]"}},
        Hostile{"SetCflAboveOne", {}, with(kRun, " --set time.cfl=2"), {"time.cfl"}},
        // Refused by the start-up check (memory, cost, stability), before any allocation.
        Hostile{"DxBeyondMemory",
                {},
                with(kRun, " --set particles.dx=1e-6"),
                {"--set", "particles.dx", "particles"}},
        Hostile{"LengthBeyondMemory", {}, with(kRun, " --set geometry.length=1e12"), {"particles"}},
        Hostile{"HugeViscosityNeverEnds",
                {},
                with(kRun, " --set fluid.nu=1e30"),
                {"fluid.nu", "never end"}},
        Hostile{"HugeDiffusivity", {}, with(kRun, " --set species.D=1e308"), {"species.D"}},
        // In a network the species that sets the diffusion limit is named, not the first.
        Hostile{"HugeDiffusivityOfTheSecondSpecies",
                {{"net.toml",
                  "name = \"n\"\n[particles]\ndx = 0.5\n[[species]]\nname = \"A\"\nD = 0.1\n"
                  "[[species]]\nname = \"B\"\nD = 1e308\n"}},
                "run net.toml --out old",
                {"species[1].D", "1e+308"}},
        Hostile{
            "FixedDtAboveTheLimit", {}, with(kRun, " --set time.dt=0.01"), {"time.dt", "--force"}},
        Hostile{"DtFactorAboveTheLimit",
                {},
                with(kRun, " --set time.dt_factor=5"),
                {"time.dt_factor", "--force"}},
        Hostile{"DtAndDtFactorBoth",
                {},
                with(kRun, " --set time.dt=1e-5 --set time.dt_factor=1"),
                {"time.dt_factor"}},
        Hostile{"JitterAboveHalfASpacing",
                {},
                with(kRun, " --set particles.jitter=0.5"),
                {"particles.jitter", "[0, 0.45]"}},
        // Options and paths.
        Hostile{"ThreadsZero", {}, with(kRun, " --threads 0"), {"--threads", "1 to 1024"}},
        Hostile{"ThreadsNegative", {}, with(kRun, " --threads -1"), {"--threads"}},
        Hostile{"ThreadsHuge", {}, with(kRun, " --threads 100000"), {"--threads", "1 to 1024"}},
        Hostile{"ThreadsWord", {}, with(kRun, " --threads many"), {"--threads"}},
        Hostile{"UnknownOption", {}, with(kRun, " --frobnicate"), {"--frobnicate"}},
        Hostile{"UnknownCommand", {}, "frobnicate", {}},
        Hostile{"NoCase", {}, "run", {"case file"}},
        Hostile{"CaseAndRestart", {}, "run {lfr} --restart old", {"not both"}},
        Hostile{"RestartNothing", {}, "run --restart nowhere", {"nowhere", "checkpoint"}},
        Hostile{"OutEmpty", {}, "run {lfr} --out ''", {"--out", "empty"}},
        Hostile{"OutIsAFile",
                {{"afile", "x"}},
                "run {lfr} --set particles.dx=0.5 --out afile",
                {"afile", "not a directory"}},
        Hostile{"OutUnderNoParent",
                {},
                "run {lfr} --set particles.dx=0.5 --out /proc/none/o",
                {"/proc/none/o"}},
        // compare with run outputs it cannot read.
        Hostile{"CompareMissingRun", {}, "compare nowhere noref", {"nowhere"}},
        Hostile{"CompareBadProbesHeader",
                {{"r/probes.csv", "x,y\n1,2\n"}, {"r/run.json", "{}"}},
                "compare r r",
                {"r/probes.csv:1", "header"}},
        Hostile{
            "CompareTruncatedProbes",
            {{"r/probes.csv", "x_mm,C_y0,C_y+2.5,C_y-2.5,C_mean\n25,1.5\n"}, {"r/run.json", "{}"}},
            "compare r r",
            {"r/probes.csv"}}),
    [](const ::testing::TestParamInfo<Hostile>& i) { return std::string(i.param.name); });

// The start-up memory check counts particles without building the scene: the count must be
// the scene's own.
TEST(Preflight, ParticleEstimateIsTheSceneCount) {
  for (const double dx : {1.0, 0.5, 0.25}) {
    Case c;
    c.particles.dx = dx;
    c.particles.inlet_layers = 7;
    c.particles.wall_layers = 4;
    EXPECT_EQ(channel_particle_estimate(c), static_cast<double>(ChannelScene(c).initial_count()))
        << "dx = " << dx;
  }
}

}  // namespace
}  // namespace adrsph
