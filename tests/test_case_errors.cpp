// Case files that cannot be read: missing, bad TOML, unknown keys, wrong types, bad enums.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "adrsph/case.hpp"
#include "io_test_util.hpp"

namespace adrsph {
namespace {

using ::testing::HasSubstr;

// Loads `text` as a case file and returns the CaseError it throws.
CaseError load_error(const std::string& text, std::filesystem::path* file_out = nullptr) {
  test::TempDir dir;
  const auto file = dir / "bad.toml";
  test::write_file(file, text);
  if (file_out) *file_out = file;
  try {
    load_case(file);
  } catch (const CaseError& e) {
    return e;
  }
  ADD_FAILURE() << "no CaseError for:\n" << text;
  return CaseError("", "", "");
}

TEST(CaseErrors, MissingFileNamesTheFile) {
  try {
    load_case("/nonexistent/dir/nothere.toml");
    FAIL() << "no error";
  } catch (const CaseError& e) {
    EXPECT_THAT(e.what(), HasSubstr("/nonexistent/dir/nothere.toml"));
    EXPECT_THAT(e.what(), HasSubstr("no such file"));
  }
}

TEST(CaseErrors, DirectoryIsNotACaseFile) {
  test::TempDir dir;
  EXPECT_THROW(load_case(dir.path()), CaseError);
}

TEST(CaseErrors, SyntaxErrorNamesFileAndLine) {
  std::filesystem::path file;
  const CaseError e = load_error("name = \"x\"\n[species]\nD = = 3\n", &file);
  EXPECT_THAT(e.what(), HasSubstr(file.string() + ":3:"));
  EXPECT_THAT(e.what(), HasSubstr("TOML syntax error"));
}

TEST(CaseErrors, UnknownKeySuggestsTheClosest) {
  std::filesystem::path file;
  const CaseError e = load_error("[species]\nDD = 3.0\n", &file);
  EXPECT_EQ(e.key(), "species.DD");
  EXPECT_EQ(e.file(), file.string());
  EXPECT_THAT(e.what(), HasSubstr(file.string()));
  EXPECT_THAT(e.what(), HasSubstr("'species.DD'"));
  EXPECT_THAT(e.what(), HasSubstr("did you mean 'species.D'?"));
  EXPECT_THAT(e.what(), HasSubstr("line 2"));
}

TEST(CaseErrors, TypoInTopLevelKey) {
  const CaseError e = load_error("schme = \"modern\"\n");
  EXPECT_EQ(e.key(), "schme");
  EXPECT_THAT(e.what(), HasSubstr("did you mean 'scheme'?"));
}

TEST(CaseErrors, KeyInTheWrongTableFindsItsHome) {
  const CaseError e = load_error("dx = 0.5\n");
  EXPECT_EQ(e.key(), "dx");
  EXPECT_THAT(e.what(), HasSubstr("did you mean 'particles.dx'?"));
}

TEST(CaseErrors, MisspelledTable) {
  const CaseError e = load_error("[specie]\nD = 3.0\n");
  EXPECT_EQ(e.key(), "specie.D");
  EXPECT_THAT(e.what(), HasSubstr("did you mean 'species.D'?"));
}

TEST(CaseErrors, NothingCloseListsTheValidKeys) {
  const CaseError e = load_error("[species]\nzzzzzzzzzzzz = 1\n");
  EXPECT_THAT(e.what(), HasSubstr("species.c_in"));
}

TEST(CaseErrors, FirstUnknownKeyInDocumentOrder) {
  const CaseError e = load_error("[time]\nzeta = 1\n[fluid]\nalpha = 2\n");
  EXPECT_EQ(e.key(), "time.zeta");
}

TEST(CaseErrors, WrongTypeNamesKeyAndExpectedType) {
  const CaseError e = load_error("[particles]\ndx = \"fine\"\n");
  EXPECT_EQ(e.key(), "particles.dx");
  EXPECT_THAT(e.what(), HasSubstr("expected a number"));
  EXPECT_THAT(e.what(), HasSubstr("string \"fine\""));
}

TEST(CaseErrors, IntegerAcceptedForNumber) {
  test::TempDir dir;
  test::write_file(dir / "int.toml", "[time]\nt_end = 5\n");
  EXPECT_DOUBLE_EQ(load_case(dir / "int.toml").time.t_end, 5.0);
}

TEST(CaseErrors, FloatRejectedForInteger) {
  const CaseError e = load_error("[particles]\nwall_layers = 3.5\n");
  EXPECT_EQ(e.key(), "particles.wall_layers");
  EXPECT_THAT(e.what(), HasSubstr("expected an integer"));
}

TEST(CaseErrors, WrongTypeForBoolean) {
  const CaseError e = load_error("[species]\nale = 1\n");
  EXPECT_EQ(e.key(), "species.ale");
  EXPECT_THAT(e.what(), HasSubstr("expected a boolean"));
}

TEST(CaseErrors, WrongTypeForString) {
  const CaseError e = load_error("name = 3\n");
  EXPECT_EQ(e.key(), "name");
  EXPECT_THAT(e.what(), HasSubstr("expected a string"));
}

TEST(CaseErrors, WrongTypeInArray) {
  const CaseError e = load_error("[output]\nfield_times = [1.0, \"two\"]\n");
  EXPECT_THAT(e.what(), HasSubstr("output.field_times[1]"));
  EXPECT_THAT(e.what(), HasSubstr("expected a number"));
}

TEST(CaseErrors, ArrayExpected) {
  const CaseError e = load_error("[output]\nfield_times = 1.0\n");
  EXPECT_EQ(e.key(), "output.field_times");
  EXPECT_THAT(e.what(), HasSubstr("expected an array"));
}

TEST(CaseErrors, NotANumber) {
  const CaseError e = load_error("[species]\nD = nan\n");
  EXPECT_EQ(e.key(), "species.D");
  EXPECT_THAT(e.what(), HasSubstr("finite"));
}

TEST(CaseErrors, BadSchemeListsAllowedValues) {
  const CaseError e = load_error("scheme = \"modrn\"\n");
  EXPECT_EQ(e.key(), "scheme");
  EXPECT_THAT(e.what(), HasSubstr("\"modern\" | \"conventional\""));
  EXPECT_THAT(e.what(), HasSubstr("\"modrn\""));
}

TEST(CaseErrors, BadFlowListsAllowedValues) {
  const CaseError e = load_error("flow = \"sph\"\n");
  EXPECT_EQ(e.key(), "flow");
  EXPECT_THAT(e.what(), HasSubstr("\"wcsph\" | \"prescribed\""));
}

TEST(CaseErrors, TableExpected) {
  const CaseError e = load_error("species = 3\n");
  EXPECT_EQ(e.key(), "species");
  EXPECT_THAT(e.what(), HasSubstr("expected a table"));
}

TEST(CaseErrors, KeyIsNotATable) {
  const CaseError e = load_error("[species.D]\nx = 1\n");
  EXPECT_EQ(e.key(), "species.D");
  EXPECT_THAT(e.what(), HasSubstr("expected a number"));
}

}  // namespace
}  // namespace adrsph
