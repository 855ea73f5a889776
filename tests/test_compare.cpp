// `compare` on synthetic runs with a known error (issue 4): reference 1.0 everywhere,
// run 1.02 -> 2.00%; the paper's table 3 row chosen by Pe and scheme from run.json.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "adrsph/probes.hpp"
#include "analysis/compare.hpp"
#include "io_test_util.hpp"

namespace adrsph {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

ProbeTable uniform_probes(double c_line, double c_mean) {
  ProbeTable t;
  t.x_mm = probe_x_positions(100.0);
  t.c_y0.assign(t.x_mm.size(), c_line);
  t.c_yp25.assign(t.x_mm.size(), c_line);
  t.c_ym25.assign(t.x_mm.size(), c_line);
  t.c_mean.assign(t.x_mm.size(), c_mean);
  return t;
}

StationTable uniform_stations(double c) {
  return {station_x_positions(100.0), {c, c, c}};
}

void write_dir(const fs::path& dir, double c_line, double c_mean) {
  fs::create_directories(dir);
  write_probes_csv(dir / "probes.csv", uniform_probes(c_line, c_mean));
  write_stations_csv(dir / "stations.csv", uniform_stations(c_mean));
}

TEST(Compare, KnownErrorOnEveryLine) {
  const analysis::LineErrors e =
      analysis::line_errors(uniform_probes(1.02, 0.97), uniform_probes(1.0, 1.0));
  ASSERT_EQ(e.x_mm.size(), 200u);
  for (std::size_t i = 0; i < e.x_mm.size(); ++i) {
    EXPECT_NEAR(e.err_y0[i], 0.02, 1e-12);
    EXPECT_NEAR(e.err_mean[i], 0.03, 1e-12);
  }
  const auto summary = analysis::summarise(e);
  EXPECT_NEAR(summary[0].max, 0.02, 1e-12);
  EXPECT_NEAR(summary[3].mean, 0.03, 1e-12);
}

TEST(Compare, ReferenceIsInterpolatedToOtherAbscissae) {
  ProbeTable ref = uniform_probes(1.0, 1.0);
  for (std::size_t i = 0; i < ref.x_mm.size(); ++i) ref.c_y0[i] = 1.0 + ref.x_mm[i];
  ProbeTable run;
  run.x_mm = {0.75};
  run.c_y0 = {1.75 * 1.1};
  run.c_yp25 = run.c_ym25 = run.c_mean = {1.0};
  EXPECT_NEAR(analysis::line_errors(run, ref).err_y0[0], 0.1, 1e-12);
  run.x_mm = {0.25};  // before the first reference probe
  EXPECT_THROW(analysis::line_errors(run, ref), std::runtime_error);
}

TEST(Compare, PaperRowsFollowSpecSection4) {
  ASSERT_TRUE(analysis::paper_table3_row(1e5));
  EXPECT_DOUBLE_EQ(analysis::paper_table3_row(1e5)->modern[0], 0.0155);
  EXPECT_DOUBLE_EQ(analysis::paper_table3_row(10.0)->conventional[2], 0.0379);
  EXPECT_DOUBLE_EQ(analysis::paper_table3_row(1000.0)->modern[1], 0.0142);
  EXPECT_FALSE(analysis::paper_table3_row(500.0));
}

TEST(Compare, RunInfoBySimpleKeySearch) {
  test::TempDir dir;
  test::write_file(dir / "run.json",
                   "{\"case\": {\"name\": \"x\", \"scheme\" : \"conventional\"},\n \"Pe\": 1e+05}");
  const auto info = analysis::read_run_info(dir / "run.json");
  ASSERT_TRUE(info.pe && info.scheme);
  EXPECT_DOUBLE_EQ(*info.pe, 1e5);
  EXPECT_EQ(*info.scheme, "conventional");
  EXPECT_FALSE(analysis::read_run_info(dir / "missing.json").pe);
  EXPECT_TRUE(info.paper_kinetics);  // no reactions: species.k, the paper's first order
}

// The paper's table 3 goes beside a run only when its kinetics are the paper's.
TEST(Compare, PaperColumnsOnlyForThePapersKinetics) {
  test::TempDir dir;
  auto info_of = [&](const std::string& reactions) {
    test::write_file(dir / "run.json",
                     "{\"scheme\": \"modern\", \"Pe\": 1000, \"reactions\": " + reactions + "}");
    return analysis::read_run_info(dir / "run.json");
  };
  EXPECT_TRUE(info_of(R"([{"law": "first_order", "k": 1.462, "zones": []}])").paper_kinetics);
  EXPECT_FALSE(info_of(R"([{"law": "michaelis_menten", "zones": []}])").paper_kinetics);
  EXPECT_FALSE(info_of(R"([{"law" : "first_order", "zones": [{"x0": 1}]}])").paper_kinetics);
  EXPECT_FALSE(
      info_of(R"([{"law": "first_order", "zones": []}, {"law": "first_order", "zones": []}])")
          .paper_kinetics);
  const auto mm = info_of(R"([{"law": "michaelis_menten", "zones": []}])");
  ASSERT_TRUE(mm.pe);
  EXPECT_DOUBLE_EQ(*mm.pe, 1000.0);  // Pe is still shown

  const std::vector<analysis::StationError> stations = {{25.0, 1.0, 1.01, 0.0099, {}, {}}};
  const std::string md = analysis::compare_markdown("run", "ref", mm, stations, {});
  EXPECT_THAT(md, testing::HasSubstr("Pe = 1000, scheme = modern"));
  EXPECT_THAT(md, testing::Not(testing::HasSubstr("paper, modern")));
  EXPECT_THAT(md, testing::HasSubstr("no paper columns"));
  analysis::RunInfo paper = mm;
  paper.paper_kinetics = true;
  EXPECT_THAT(analysis::compare_markdown("run", "ref", paper, stations, {}),
              testing::HasSubstr("paper, modern"));
}

// The command end to end: 2.00% in the table, the paper's conventional Pe = 1000 column.
TEST(Compare, CommandWritesTheTableAndTheCsv) {
  test::TempDir dir;
  write_dir(dir / "run", 1.02, 1.02);
  write_dir(dir / "ref", 1.0, 1.0);
  test::write_file(dir / "run" / "run.json", "{\"scheme\": \"conventional\", \"Pe\": 1000}\n");
  const auto r = test::run_adrsph("compare run ref --no-plot", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("| 25 | 1.000000 | 1.020000 | 2.00% | 0.88% |"));
  EXPECT_THAT(r.out, HasSubstr("| 100 | 1.000000 | 1.020000 | 2.00% | 3.34% |"));
  EXPECT_THAT(r.out, HasSubstr("| y = 0 | 2.00% | 2.00% |"));
  EXPECT_EQ(test::read_file(dir / "run" / "compare.md").find("# run against ref"), 0u);
  const std::string csv = test::read_file(dir / "run" / "compare.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "x_mm,err_y0,err_y+2.5,err_y-2.5,err_mean");
  EXPECT_THAT(csv, HasSubstr("\n0.5,0.02,0.02,0.02,0.02\n"));
}

TEST(Compare, CommandWithoutRunJsonShowsBothPaperColumnsFromTheReferencePe) {
  test::TempDir dir;
  write_dir(dir / "run", 0.99, 0.99);
  write_dir(dir / "ref", 1.0, 1.0);
  test::write_file(dir / "ref" / "reference.json", "{\"Pe\": 100000}\n");
  const auto r = test::run_adrsph("compare run ref --no-plot --out report/cmp.md", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("| 25 | 1.000000 | 0.990000 | 1.00% | 1.55% | 0.26% |"));
  EXPECT_TRUE(fs::exists(dir / "report" / "cmp.md"));
  EXPECT_TRUE(fs::exists(dir / "report" / "cmp.csv"));
}

TEST(Compare, CommandNamesAMalformedFile) {
  test::TempDir dir;
  write_dir(dir / "run", 1.0, 1.0);
  fs::create_directories(dir / "ref");
  test::write_file(dir / "ref" / "probes.csv", "x_mm,C_y0,C_y+2.5,C_y-2.5,C_mean\n0.5,1,1,1\n");
  const auto r = test::run_adrsph("compare run ref --no-plot", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("probes.csv:2"));
}

}  // namespace
}  // namespace adrsph
