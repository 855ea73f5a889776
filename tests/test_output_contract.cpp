// The output contract of `adrsph run` after a tiny run: run.json keys, probes.csv and
// stations.csv headers and rows, fields.h5 + fields.xmf.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "adrsph/io/fields_h5.hpp"
#include "io_test_util.hpp"

namespace adrsph {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);)
    if (!l.empty()) out.push_back(l);
  return out;
}

class OutputContract : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new test::TempDir();
    fs::create_directories(dir_->path() / "out");
    test::write_file(dir_->path() / "out" / "run.json", "{}");  // an earlier run: replaced
    result_ = test::run_adrsph("run '" + (test::source_dir() / "cases" / "lfr.toml").string() +
                                   "' --set time.max_steps=3 --set particles.dx=0.5"
                                   " --set flow=prescribed --out out --threads 1",
                               dir_->path());
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  void SetUp() override { ASSERT_EQ(result_.exit_code, 0) << result_.out << result_.err; }
  static fs::path out() { return dir_->path() / "out"; }

  static test::TempDir* dir_;
  static test::CommandResult result_;
};
test::TempDir* OutputContract::dir_ = nullptr;
test::CommandResult OutputContract::result_;

TEST_F(OutputContract, RunJson) {
  const auto j = nlohmann::json::parse(test::read_file(out() / "run.json"));
  for (const char* key : test::kRunJsonKeys) EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["case"], "lfr");
  EXPECT_EQ(j["scheme"], "modern");
  EXPECT_EQ(j["flow"], "prescribed");
  EXPECT_DOUBLE_EQ(j["dx"].get<double>(), 0.5);
  EXPECT_EQ(j["steps"], 3);
  EXPECT_EQ(j["threads"], 1);
  EXPECT_EQ(j["status"], "ok");
  EXPECT_GT(j["particles"].get<long>(), 0);
  EXPECT_GT(j["fluid_particles"].get<long>(), 0);
  EXPECT_GT(j["t_reached"].get<double>(), 0.0);
  EXPECT_TRUE(j["phase_seconds"].is_object());
  for (const char* x : {"25", "50", "100"}) EXPECT_TRUE(j["stations"].contains(x)) << x;
}

TEST_F(OutputContract, ProbesCsv) {
  const auto l = lines(test::read_file(out() / "probes.csv"));
  ASSERT_EQ(l.size(), 201u);  // header + x = 0.5, 1.0, ..., 100
  EXPECT_EQ(l[0], "x_mm,C_y0,C_y+2.5,C_y-2.5,C_mean");
  EXPECT_THAT(l[1], ::testing::StartsWith("0.5,"));
  EXPECT_THAT(l[200], ::testing::StartsWith("100,"));
}

TEST_F(OutputContract, StationsCsv) {
  const auto l = lines(test::read_file(out() / "stations.csv"));
  ASSERT_EQ(l.size(), 4u);
  EXPECT_EQ(l[0], "x_mm,C_mean");
  EXPECT_THAT(l[1], ::testing::StartsWith("25,"));
  EXPECT_THAT(l[2], ::testing::StartsWith("50,"));
  EXPECT_THAT(l[3], ::testing::StartsWith("100,"));
}

TEST_F(OutputContract, Fields) {
  ASSERT_TRUE(fs::exists(out() / "fields.h5"));
  ASSERT_TRUE(fs::exists(out() / "fields.xmf"));
  const std::size_t n = count_field_frames(out() / "fields.h5");
  ASSERT_GE(n, 1u);  // at least the final state
  const FieldData last = read_field_frame(out() / "fields.h5", n - 1);
  EXPECT_GT(last.x.size(), 0u);
  EXPECT_EQ(last.kind.size(), last.x.size());
  EXPECT_EQ(last.step, 3);
  EXPECT_THAT(test::read_file(out() / "fields.xmf"),
              HasSubstr("fields.h5:/" + field_frame_name(n - 1) + "/x"));
}

TEST_F(OutputContract, SummaryAndNoStaging) {
  EXPECT_THAT(result_.out, HasSubstr("lfr"));
  EXPECT_THAT(result_.out, HasSubstr("steady state"));
  EXPECT_THAT(result_.out, HasSubstr("x = 25"));
  EXPECT_THAT(result_.err, ::testing::Not(HasSubstr("\r")));  // no progress line off a terminal
  for (const auto& e : fs::directory_iterator(dir_->path()))
    EXPECT_EQ(e.path().filename().string().find(".partial"), std::string::npos) << e.path();
}

}  // namespace
}  // namespace adrsph
