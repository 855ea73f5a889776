// `adrsph study`: the study file's errors, the matrix it expands to, --only, and one tiny
// study end to end through the built binary (runs, references, compares, study.json,
// refusal without --resume, skipping done runs with it).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include "adrsph/simulation.hpp"
#include "analysis/study_plan.hpp"
#include "io_test_util.hpp"

namespace adrsph {
namespace {

using analysis::StudyError;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Not;
namespace fs = std::filesystem;

std::string lfr_path() {
  return (test::source_dir() / "cases" / "lfr.toml").string();
}

// The message of the StudyError that parsing (and expanding) `text` throws; empty if none.
std::string study_error(const std::string& text, const fs::path& file = "my_study.toml") {
  try {
    analysis::expand_study(analysis::parse_study_text(text, file));
  } catch (const StudyError& e) {
    return e.what();
  }
  return {};
}

// A study text on the shipped lfr.toml (absolute path) with one group's body.
std::string with_group(const std::string& body) {
  return "case = \"" + lfr_path() + "\"\n[[group]]\nname = \"g\"\n" + body;
}

const analysis::StudyRun& find_run(const std::vector<analysis::StudyRun>& runs,
                                   const std::string& name) {
  const auto it = std::find_if(runs.begin(), runs.end(),
                               [&](const analysis::StudyRun& r) { return r.name == name; });
  if (it == runs.end()) throw std::runtime_error("no run " + name);
  return *it;
}

TEST(StudyPlan, MissingCaseNamesFileAndKey) {
  const std::string e = study_error("name = \"x\"\n[[group]]\nname = \"g\"\n");
  EXPECT_THAT(e, HasSubstr("my_study.toml"));
  EXPECT_THAT(e, HasSubstr("key 'case'"));
  EXPECT_THAT(e, HasSubstr("missing"));
}

TEST(StudyPlan, AxisOfTheWrongTypeNamesGroupAndKey) {
  std::string e = study_error(with_group("dx = [0.5, \"fine\"]\n"));
  EXPECT_THAT(e, HasSubstr("my_study.toml: group 'g': key 'dx'"));
  EXPECT_THAT(e, HasSubstr("expected a number > 0"));
  EXPECT_THAT(e, HasSubstr("string \"fine\""));

  e = study_error(with_group("scheme = [\"modern\", 3]\n"));
  EXPECT_THAT(e, HasSubstr("group 'g': key 'scheme'"));
  EXPECT_THAT(e, HasSubstr("expected a string or a list of strings"));

  e = study_error(with_group("Pe = [10, -1]\n"));
  EXPECT_THAT(e, HasSubstr("key 'Pe'"));
  EXPECT_THAT(e, HasSubstr("integer -1"));

  e = study_error(with_group("Pe = []\n"));
  EXPECT_THAT(e, HasSubstr("key 'Pe'"));
  EXPECT_THAT(e, HasSubstr("non-empty list"));
}

TEST(StudyPlan, UnknownCaseKeyInSetNamesFileGroupAndKey) {
  const std::string e =
      study_error(with_group("Pe = [10, 1000]\nset = { \"species.DD\" = 1.0 }\n"), "dir/s.toml");
  EXPECT_THAT(e, HasSubstr("dir/s.toml"));
  EXPECT_THAT(e, HasSubstr("group 'g', run 'g-pe10'"));
  EXPECT_THAT(e, HasSubstr("key 'set.species.DD'"));
  EXPECT_THAT(e, HasSubstr("did you mean 'species.D'?"));
}

TEST(StudyPlan, BadCaseValueNamesTheRun) {
  const std::string e = study_error(with_group("scheme = [\"modern\", \"modrn\"]\n"));
  EXPECT_THAT(e, HasSubstr("run 'g-modrn'"));
  EXPECT_THAT(e, HasSubstr("key 'scheme'"));
}

TEST(StudyPlan, OtherStructuralErrors) {
  EXPECT_THAT(study_error(with_group("colour = [\"red\"]\n")),
              HasSubstr("key 'colour': unknown group key"));
  EXPECT_THAT(study_error("case = \"x.toml\"\nthreds = 2\n[[group]]\nname = \"g\"\n"),
              HasSubstr("key 'threds': unknown key"));
  EXPECT_THAT(study_error(with_group("dx = 0.5\n\"particles.dx\" = 0.25\n")),
              HasSubstr("sets particles.dx, which 'dx' sets already"));
  EXPECT_THAT(study_error("case = \"" + lfr_path() + "\"\n[[group]]\nscheme = \"modern\"\n"),
              HasSubstr("group 1: key 'name'"));
  EXPECT_THAT(study_error("case = \"nothere.toml\"\n[[group]]\nname = \"g\"\n"),
              HasSubstr("key 'case': the base case does not load"));
  // Two groups whose runs get one name.
  EXPECT_THAT(study_error(with_group("scheme = \"modern\"\n[[group]]\nname = \"g\"\n")),
              HasSubstr("two groups have this name"));
  // The reference of a Pe is the base case's physics: a group may not change it.
  EXPECT_THAT(study_error(with_group("Pe = [1000]\n\"species.k\" = 2.0\n")),
              HasSubstr("key 'species.k': gives species.k = 2"));
}

TEST(StudyPlan, PaperStudyExpandsInFileOrder) {
  const auto study = analysis::parse_study(test::source_dir() / "cases" / "paper_study.toml");
  EXPECT_EQ(study.name, "paper_study");
  EXPECT_EQ(study.reference_nx, 1600);
  EXPECT_EQ(study.threads, 2);
  const auto runs = analysis::expand_study(study);
  ASSERT_EQ(runs.size(), 9u + 18u + 6u + 3u + 2u);
  // Groups in file order; within a group the last axis (dx) fastest.
  EXPECT_EQ(runs[0].name, "prescribed-pe10-dx0.5");
  EXPECT_EQ(runs[1].name, "prescribed-pe10-dx0.25");
  EXPECT_EQ(runs[2].name, "prescribed-pe10-dx0.125");
  EXPECT_EQ(runs[3].name, "prescribed-pe1000-dx0.5");
  EXPECT_EQ(runs[9].name, "paper-conventional-pe10-dx0.5");
  EXPECT_EQ(runs[18].name, "paper-modern-pe10-dx0.5");
  EXPECT_EQ(runs[18].group, "paper-modern");
  EXPECT_EQ(runs[26].name, "paper-modern-pe100000-dx0.125");
  EXPECT_EQ(runs[27].name, "warm-conventional-pe10-dx0.5");
  EXPECT_EQ(runs[35].name, "ale-pe100000");
  EXPECT_EQ(runs[35].group, "ale");
  EXPECT_EQ(runs.back().name, "c0-pe100000");
  EXPECT_EQ(runs.back().group, "c0");

  // Pe -> species.D = u_bulk L / Pe = 1e4 / Pe.
  const auto& pe10 = find_run(runs, "paper-modern-pe10-dx0.25");
  EXPECT_DOUBLE_EQ(pe10.D, 1000.0);
  EXPECT_DOUBLE_EQ(pe10.pe, 10.0);
  EXPECT_EQ(pe10.pe_label, "10");
  EXPECT_THAT(pe10.sets, ElementsAre("time.warm_start=false", "time.cfl=0.75", "scheme=modern",
                                     "species.D=1000", "particles.dx=0.25"));
  EXPECT_THAT(find_run(runs, "paper-conventional-pe10-dx0.25").sets,
              ElementsAre("time.warm_start=false", "scheme=conventional", "species.D=1000",
                          "particles.dx=0.25"));
  EXPECT_DOUBLE_EQ(find_run(runs, "prescribed-pe100000-dx0.5").D, 0.1);
  EXPECT_EQ(find_run(runs, "prescribed-pe100000-dx0.5").pe_label, "100000");
  EXPECT_THAT(find_run(runs, "prescribed-pe1000-dx0.125").sets,
              ElementsAre("time.cfl=1", "particles.skin=0.2", "flow=prescribed", "species.D=10",
                          "particles.dx=0.125"));
  EXPECT_THAT(find_run(runs, "ale-pe1000").sets,
              ElementsAre("time.cfl=0.75", "scheme=modern", "species.D=10", "particles.dx=0.25",
                          "species.ale=true"));
  EXPECT_EQ(find_run(runs, "warm-modern-pe1000-dx0.5").sets[0], "time.warm_start=true");
  // The speed of sound is the flow's, not the reference's: a group may change it.
  EXPECT_THAT(find_run(runs, "c0-pe1000").sets,
              ElementsAre("time.warm_start=false", "time.cfl=0.75", "scheme=modern", "species.D=10",
                          "particles.dx=0.25", "fluid.c0_factor=20"));
}

TEST(StudyPlan, CaseKeyAxesNameRunsByTheirLastComponent) {
  const auto runs = analysis::expand_study(analysis::parse_study_text(
      with_group("\"species.ale\" = [false, true]\nPe = 100\n\"time.cfl\" = [0.5]\n"), "s.toml"));
  ASSERT_EQ(runs.size(), 2u);
  EXPECT_EQ(runs[0].name, "g-alefalse-cfl0.5");
  EXPECT_EQ(runs[1].name, "g-aletrue-cfl0.5");
  EXPECT_THAT(runs[1].sets, ElementsAre("species.ale=true", "species.D=100", "time.cfl=0.5"));
  EXPECT_EQ(runs[1].pe_label, "100");
}

// `force` passes --force to a group's runs (the stability map's steps above the limit);
// `report` picks the report tool. The shipped stress study expands with both.
TEST(StudyPlan, ForceAndReport) {
  const auto study = analysis::parse_study_text(
      with_group("force = true\n\"time.dt_factor\" = [2.0, 6.0]\n[[group]]\nname = \"h\"\n"),
      "s.toml");
  EXPECT_EQ(study.report, "study");
  const auto runs = analysis::expand_study(study);
  ASSERT_EQ(runs.size(), 3u);
  EXPECT_TRUE(runs[0].force);
  EXPECT_TRUE(runs[1].force);
  EXPECT_FALSE(runs[2].force);
  EXPECT_THAT(runs[1].sets, ElementsAre("time.dt_factor=6"));
  EXPECT_THAT(study_error(with_group("force = \"yes\"\n")),
              HasSubstr("key 'force': expected true or false"));
  EXPECT_THAT(study_error("report = \"table\"\n" + with_group("")),
              HasSubstr("key 'report': expected \"study\""));

  const auto stress = analysis::parse_study(test::source_dir() / "cases" / "stress_study.toml");
  EXPECT_EQ(stress.report, "stress");
  const auto map = analysis::expand_study(stress);
  EXPECT_EQ(map.size(), 57u);
  EXPECT_TRUE(find_run(map, "dt-modern-dt_factor8").force);
  EXPECT_FALSE(find_run(map, "jitter-modern-jitter0.4").force);
  EXPECT_DOUBLE_EQ(find_run(map, "pe-conventional-pe0.1").D, 1e5);
}

TEST(StudyPlan, OnlyPatterns) {
  const auto p = analysis::split_patterns({"paper-*-pe1000-*,ale-*", "warm-modern-pe10-dx0.5"});
  EXPECT_THAT(p, ElementsAre("paper-*-pe1000-*", "ale-*", "warm-modern-pe10-dx0.5"));
  EXPECT_TRUE(analysis::run_selected("paper-modern-pe1000-dx0.25", p));
  EXPECT_TRUE(analysis::run_selected("ale-pe10", p));
  EXPECT_TRUE(analysis::run_selected("warm-modern-pe10-dx0.5", p));
  EXPECT_FALSE(analysis::run_selected("paper-modern-pe100000-dx0.25", p));
  EXPECT_FALSE(analysis::run_selected("warm-modern-pe10-dx0.25", p));
  EXPECT_TRUE(analysis::run_selected("anything", {}));
}

// Two tiny prescribed-flow runs (20 steps) and a coarse reference.
std::string tiny_study(int max_steps) {
  return "name = \"tiny\"\ncase = \"" + lfr_path() +
         "\"\nruns_dir = \"runs\"\nthreads = 2\n"
         "[reference]\nnx = 200\nny = 20\n"
         "[[group]]\nname = \"t\"\nflow = \"prescribed\"\nPe = [1000, 100000]\ndx = 0.5\n"
         "set = { \"time.max_steps\" = " +
         std::to_string(max_steps) + ", \"output.field_times\" = [] }\n";
}

TEST(StudyCli, TinyStudyRunsOnceAndResumes) {
  test::TempDir dir;
  test::write_file(dir / "tiny.toml", tiny_study(20));
  const fs::path runs = dir / "runs";

  auto r = test::run_adrsph("study tiny.toml --dry-run", dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("t-pe1000"));
  EXPECT_THAT(r.out, HasSubstr("new"));
  EXPECT_FALSE(fs::exists(runs));

  EXPECT_EQ(test::run_adrsph("study tiny.toml --only 'x*'", dir.path()).exit_code, 2);

  r = test::run_adrsph("study tiny.toml", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_THAT(r.out, HasSubstr("[1/2] t-pe1000: started"));
  EXPECT_THAT(r.out, HasSubstr("[2/2] t-pe100000: ok"));
  for (const char* name : {"t-pe1000", "t-pe100000"}) {
    EXPECT_TRUE(fs::exists(runs / name / "run.json")) << name;
    EXPECT_TRUE(fs::exists(runs / name / "compare.csv")) << name;
    EXPECT_TRUE(fs::exists(runs / (std::string(name) + ".args.json"))) << name;
    EXPECT_TRUE(fs::exists(runs / (std::string(name) + ".log"))) << name;
  }
  EXPECT_TRUE(fs::exists(runs / "reference" / "pe1000" / "stations.csv"));
  EXPECT_TRUE(fs::exists(runs / "reference" / "pe100000" / "stations.csv"));
  const auto study = nlohmann::json::parse(test::read_file(runs / "study.json"));
  EXPECT_EQ(study["name"], "tiny");
  ASSERT_EQ(study["runs"].size(), 2u);
  EXPECT_EQ(study["runs"][1]["name"], "t-pe100000");
  EXPECT_EQ(study["runs"][1]["status"], "done");
  EXPECT_EQ(study["runs"][1]["reference"], "reference/pe100000");
  EXPECT_EQ(study["runs"][1]["sets"][3], "species.D=0.1");
  EXPECT_EQ(study["references"].size(), 2u);

  // Again without --resume: refused, nothing touched.
  const auto t0 = fs::last_write_time(runs / "t-pe1000" / "run.json");
  const auto t1 = fs::last_write_time(runs / "t-pe100000" / "run.json");
  r = test::run_adrsph("study tiny.toml", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--resume"));

  // With --resume: both runs are done and skipped.
  r = test::run_adrsph("study tiny.toml --resume", dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_THAT(r.out, Not(HasSubstr("started")));
  EXPECT_EQ(fs::last_write_time(runs / "t-pe1000" / "run.json"), t0);
  EXPECT_EQ(fs::last_write_time(runs / "t-pe100000" / "run.json"), t1);
  r = test::run_adrsph("study tiny.toml --dry-run", dir.path());
  EXPECT_THAT(r.out, HasSubstr("done"));
  EXPECT_THAT(r.out, Not(HasSubstr("new")));

  // The study file now gives the runs other arguments: --resume stops, naming a run.
  test::write_file(dir / "tiny.toml", tiny_study(21));
  r = test::run_adrsph("study tiny.toml --resume", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("run 't-pe1000'"));
  EXPECT_THAT(r.err, HasSubstr("--rerun-changed"));
  EXPECT_EQ(fs::last_write_time(runs / "t-pe1000" / "run.json"), t0);

  // On a machine without the runs directory, --resume takes the done runs back from the
  // report's copies instead of computing them again. (A report needs Debian's python3 with
  // matplotlib, which tools/setup.sh installs.)
  test::write_file(dir / "tiny.toml", tiny_study(20));
  if (fs::exists(runs / "report" / "runs" / "t-pe1000" / "run.json")) {
    fs::rename(runs / "report", dir / "kept_report");
    fs::remove_all(runs);
    // Started there without --resume, the study runs what it is asked to but leaves the report
    // alone: written from the runs directory, it would delete the report's other done run.
    r = test::run_adrsph("study tiny.toml --only t-pe1000 --report kept_report", dir.path());
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_THAT(r.out, HasSubstr("t-pe1000: started"));
    EXPECT_THAT(r.out, HasSubstr("report: not written"));
    EXPECT_THAT(r.out, HasSubstr("(e.g. t-pe100000)"));
    EXPECT_TRUE(fs::exists(dir / "kept_report" / "runs" / "t-pe100000" / "run.json"));
    fs::remove_all(runs);
    // --only one run: the other, restored, still gets its reference, which the report needs.
    r = test::run_adrsph("study tiny.toml --resume --only t-pe1000 --report kept_report",
                         dir.path());
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_THAT(r.out, HasSubstr("t-pe100000: done, restored from the report"));
    EXPECT_TRUE(fs::exists(runs / "reference" / "pe100000" / "stations.csv"));
    fs::remove_all(runs);
    r = test::run_adrsph("study tiny.toml --resume --report kept_report", dir.path());
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_THAT(r.out, HasSubstr("t-pe1000: done, restored from the report"));
    EXPECT_THAT(r.out, Not(HasSubstr("t-pe1000: started")));
    EXPECT_TRUE(fs::exists(runs / "t-pe100000" / "stations.csv"));

    // A restored run has no args.json; its run.json `overrides` still say what it was made
    // with, so a study file that now gives other settings is noticed, and the report's
    // copies made with other settings are not restored.
    EXPECT_FALSE(fs::exists(runs / "t-pe1000.args.json"));
    test::write_file(dir / "tiny.toml", tiny_study(21));
    r = test::run_adrsph("study tiny.toml --resume --dry-run", dir.path());
    EXPECT_THAT(r.out, HasSubstr("CHANGED"));
    r = test::run_adrsph("study tiny.toml --resume", dir.path());
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_THAT(r.err, HasSubstr("run 't-pe1000'"));
    fs::remove_all(runs);
    r = test::run_adrsph("study tiny.toml --resume --only t-pe1000 --report changed_report",
                         dir.path());
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_THAT(r.out, Not(HasSubstr("restored")));
    EXPECT_THAT(r.out, HasSubstr("t-pe1000: started"));
    test::write_file(dir / "tiny.toml", tiny_study(20));
    fs::remove_all(runs);
    r = test::run_adrsph("study tiny.toml --resume --report kept_report", dir.path());
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_THAT(r.out, HasSubstr("t-pe1000: done, restored from the report"));

    // A run of an engine that computed differently (run.json without the current
    // results_version) is stale: moved aside and run again, never mixed into the study; the
    // report's copy of an older engine is not restored either.
    auto downgrade = [](const fs::path& run_json) {
      auto j = nlohmann::json::parse(test::read_file(run_json));
      j.erase("results_version");  // as written before version 2
      test::write_file(run_json, j.dump(2));
    };
    downgrade(runs / "t-pe1000" / "run.json");
    r = test::run_adrsph("study tiny.toml --resume --dry-run", dir.path());
    EXPECT_THAT(r.out, HasSubstr("stale"));
    r = test::run_adrsph("study tiny.toml --resume --only t-pe1000 --report kept_report",
                         dir.path());
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_THAT(r.out, HasSubstr("t-pe1000: computed by an engine of another results version"));
    EXPECT_THAT(r.out, HasSubstr("t-pe1000: started"));
    EXPECT_TRUE(fs::exists(runs / "stale" / "t-pe1000.v1" / "t-pe1000" / "run.json"));
    const auto again = nlohmann::json::parse(test::read_file(runs / "t-pe1000" / "run.json"));
    EXPECT_EQ(again["results_version"], kResultsVersion);

    downgrade(dir / "kept_report" / "runs" / "t-pe100000" / "run.json");
    fs::remove_all(runs);
    r = test::run_adrsph("study tiny.toml --resume --only t-pe100000 --report kept_report",
                         dir.path());
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_THAT(r.out, Not(HasSubstr("t-pe100000: done, restored")));
    EXPECT_THAT(r.out, HasSubstr("t-pe100000: started"));
  } else {
    ADD_FAILURE() << "no report written: " << test::read_file(runs / "report.log");
  }
}

TEST(StudyCli, RerunChangedMovesChangedRunsAsideAndRunsThemAgain) {
  test::TempDir dir;
  test::write_file(dir / "tiny.toml", tiny_study(20));
  const fs::path runs = dir / "runs";
  auto r = test::run_adrsph("study tiny.toml --only t-pe1000 --report rep", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;

  test::write_file(dir / "tiny.toml", tiny_study(21));
  r = test::run_adrsph("study tiny.toml --resume --only t-pe1000 --report rep", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("--rerun-changed"));
  r = test::run_adrsph("study tiny.toml --resume --rerun-changed --only t-pe1000 --report rep",
                       dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_THAT(r.out, HasSubstr("t-pe1000: the study file now gives it other arguments"));
  EXPECT_THAT(r.out, HasSubstr("t-pe1000: started"));
  // The old run is kept aside, the new one has the study file's arguments.
  const auto old = nlohmann::json::parse(
      test::read_file(runs / "stale" / "t-pe1000.changed" / "t-pe1000" / "run.json"));
  const auto now = nlohmann::json::parse(test::read_file(runs / "t-pe1000" / "run.json"));
  EXPECT_EQ(old["steps"], 20);
  EXPECT_EQ(now["steps"], 21);
  r = test::run_adrsph("study tiny.toml --resume --only t-pe1000 --report rep", dir.path());
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_THAT(r.out, Not(HasSubstr("started")));
}

}  // namespace
}  // namespace adrsph
