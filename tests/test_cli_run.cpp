// The built `adrsph run`: bad input exits 2, names the problem, and writes nothing.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io_test_util.hpp"

namespace adrsph {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

// The shipped case file, shell-quoted. (Appending, not `"'" + ...`, avoids GCC 12's false
// -Wrestrict on string concatenation.)
std::string lfr() {
  std::string s(1, '\'');
  s += (test::source_dir() / "cases" / "lfr.toml").string();
  s += '\'';
  return s;
}

// An earlier run's output directory, to check that it survives a failed start.
void make_old_output(const fs::path& out) {
  fs::create_directories(out);
  test::write_file(out / "run.json", "{\"old\": true}\n");
  test::write_file(out / "probes.csv", "old\n");
}

void expect_old_output(const fs::path& out) {
  EXPECT_EQ(test::read_file(out / "run.json"), "{\"old\": true}\n");
  EXPECT_EQ(test::read_file(out / "probes.csv"), "old\n");
  EXPECT_EQ(std::distance(fs::directory_iterator(out), fs::directory_iterator{}), 2);
}

// No DIR.partial left next to the output directory.
void expect_no_staging(const fs::path& parent) {
  for (const auto& e : fs::directory_iterator(parent))
    EXPECT_EQ(e.path().filename().string().find(".partial"), std::string::npos) << e.path();
}

TEST(CliRun, TypoInKeyExits2AndLeavesOutputAlone) {
  test::TempDir dir;
  test::write_file(dir / "typo.toml", "name = \"typo\"\n[species]\nDD = 10.0\n");
  make_old_output(dir / "out");
  const auto r = test::run_adrsph("run typo.toml --out out", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("typo.toml"));
  EXPECT_THAT(r.err, HasSubstr("species.DD"));
  EXPECT_THAT(r.err, HasSubstr("did you mean 'species.D'?"));
  expect_old_output(dir / "out");
  expect_no_staging(dir.path());
}

TEST(CliRun, NonPhysicalValueExits2) {
  test::TempDir dir;
  make_old_output(dir / "out");
  const auto r = test::run_adrsph("run " + lfr() + " --set species.D=-1 --out out", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("species.D"));
  EXPECT_THAT(r.err, HasSubstr(">= 0"));
  expect_old_output(dir / "out");
}

TEST(CliRun, DxThatDoesNotFitExits2) {
  test::TempDir dir;
  const auto r = test::run_adrsph("run " + lfr() + " --set particles.dx=0.3", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("particles.dx"));
  EXPECT_FALSE(fs::exists(dir / "runs"));
}

TEST(CliRun, UnknownSetKeyExits2) {
  test::TempDir dir;
  const auto r = test::run_adrsph("run " + lfr() + " --set species.DD=1", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--set"));
  EXPECT_THAT(r.err, HasSubstr("species.DD"));
}

TEST(CliRun, MissingCaseFileExits2) {
  test::TempDir dir;
  const auto r = test::run_adrsph("run nothere.toml", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("nothere.toml"));
  EXPECT_FALSE(fs::exists(dir / "runs"));
}

TEST(CliRun, SyntaxErrorExits2WithLine) {
  test::TempDir dir;
  test::write_file(dir / "syntax.toml", "name = \"s\"\n\n[time\n");
  const auto r = test::run_adrsph("run syntax.toml", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("syntax.toml:3"));
}

TEST(CliRun, RefusesToReplaceAForeignDirectory) {
  test::TempDir dir;
  fs::create_directories(dir / "mine");
  test::write_file(dir / "mine" / "notes.txt", "keep");
  const auto r = test::run_adrsph("run " + lfr() + " --out mine", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("mine"));
  EXPECT_EQ(test::read_file(dir / "mine" / "notes.txt"), "keep");
}

TEST(CliRun, BadOptionExits2) {
  test::TempDir dir;
  EXPECT_EQ(test::run_adrsph("run " + lfr() + " --threads 0", dir.path()).exit_code, 2);
  EXPECT_EQ(test::run_adrsph("run " + lfr() + " --bogus", dir.path()).exit_code, 2);
  EXPECT_EQ(test::run_adrsph("run", dir.path()).exit_code, 2);
}

TEST(CliRun, NumericalFailureWritesOutputsAndExits3) {
  test::TempDir dir;
  make_old_output(dir / "out");
  // A fixed time step 200x above the acoustic limit blows the flow up within a few steps
  // (refused at start without --force: test_hostile_input.cpp).
  const auto r = test::run_adrsph("run " + lfr() +
                                      " --set particles.dx=0.5 --set time.dt=0.01"
                                      " --set time.max_steps=50 --force --out out",
                                  dir.path());
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_THAT(r.err, HasSubstr("failed"));
  const std::string json = test::read_file(dir / "out" / "run.json");
  EXPECT_THAT(json, HasSubstr("\"status\": \"failed\""));
  EXPECT_TRUE(fs::exists(dir / "out" / "fields.h5"));  // the last good state
  EXPECT_FALSE(fs::exists(dir / "out" / "probes.csv") &&
               test::read_file(dir / "out" / "probes.csv") == "old\n");
  expect_no_staging(dir.path());
}

TEST(CliRun, HelpDescribesEveryOption) {
  test::TempDir dir;
  const auto r = test::run_adrsph("run --help", dir.path());
  EXPECT_EQ(r.exit_code, 0);
  for (const char* s :
       {"--set", "--out", "--threads", "--quiet", "--force", "runs/<case name>", "Exit codes"})
    EXPECT_THAT(r.out, HasSubstr(s));
  EXPECT_EQ(test::run_adrsph("--help", dir.path()).exit_code, 0);
}

}  // namespace
}  // namespace adrsph
