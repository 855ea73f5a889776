// StagedDir: an output directory is replaced whole, or left alone.
#include <gtest/gtest.h>

#include "adrsph/io/output_dir.hpp"
#include "io_test_util.hpp"

namespace adrsph {
namespace {

namespace fs = std::filesystem;

TEST(OutputDir, CommitReplacesTheOldRun) {
  test::TempDir dir;
  const auto out = dir / "run";
  fs::create_directories(out);
  test::write_file(out / "run.json", "old");
  test::write_file(out / "stale.csv", "old");
  {
    StagedDir s(out);
    EXPECT_NE(s.path(), out);
    EXPECT_EQ(s.path().parent_path(), out.parent_path());
    test::write_file(s.path() / "run.json", "new");
    EXPECT_EQ(test::read_file(out / "run.json"), "old");  // untouched until commit
    s.commit();
  }
  EXPECT_EQ(test::read_file(out / "run.json"), "new");
  EXPECT_FALSE(fs::exists(out / "stale.csv"));
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator{}), 1);
}

TEST(OutputDir, NoCommitLeavesTheOldRunAndNoStaging) {
  test::TempDir dir;
  const auto out = dir / "run";
  fs::create_directories(out);
  test::write_file(out / "run.json", "old");
  {
    StagedDir s(out);
    test::write_file(s.path() / "run.json", "new");
  }
  EXPECT_EQ(test::read_file(out / "run.json"), "old");
  EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator{}), 1);
}

// DIR.partial without a checkpoint (a run killed before its first one) is removed by the next
// run into DIR, which is told so; an earlier complete DIR stays until that run commits.
TEST(OutputDir, StaleStagingIsRemovedAndReported) {
  test::TempDir dir;
  const auto out = dir / "run";
  fs::create_directories(out);
  test::write_file(out / "run.json", "old");
  fs::create_directories(dir / "run.partial");
  test::write_file(dir / "run.partial" / "fields.h5", "half-written");
  {
    StagedDir s(out);
    EXPECT_TRUE(s.removed_stale());
    EXPECT_FALSE(fs::exists(s.path() / "fields.h5"));
    EXPECT_EQ(test::read_file(out / "run.json"), "old");
  }
  StagedDir clean(out);
  EXPECT_FALSE(clean.removed_stale());
}

TEST(OutputDir, CreatesParentsAndAcceptsTrailingSlash) {
  test::TempDir dir;
  {
    StagedDir s((dir / "a" / "b" / "run").string() + "/");
    EXPECT_EQ(s.final_path(), dir / "a" / "b" / "run");
    s.commit();
  }
  EXPECT_TRUE(fs::is_directory(dir / "a" / "b" / "run"));
}

TEST(OutputDir, RefusesADirectoryThatIsNotAnOutput) {
  test::TempDir dir;
  const auto out = dir / "mine";
  fs::create_directories(out);
  test::write_file(out / "thesis.tex", "precious");
  EXPECT_THROW(StagedDir{out}, std::runtime_error);
  EXPECT_EQ(test::read_file(out / "thesis.tex"), "precious");
}

TEST(OutputDir, RefusesAFile) {
  test::TempDir dir;
  test::write_file(dir / "file", "x");
  EXPECT_THROW(StagedDir{dir / "file"}, std::runtime_error);
}

TEST(OutputDir, RefusesTheWorkingDirectory) {
  EXPECT_THROW(StagedDir{"."}, std::runtime_error);
  EXPECT_THROW(StagedDir{fs::current_path()}, std::runtime_error);
  EXPECT_THROW(StagedDir{fs::current_path().parent_path()}, std::runtime_error);
}

}  // namespace
}  // namespace adrsph
