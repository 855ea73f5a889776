// --set key=value overrides: numbers, strings (bare or quoted), booleans, arrays, errors.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "adrsph/case.hpp"
#include "io_test_util.hpp"

namespace adrsph {
namespace {

using ::testing::HasSubstr;

Case lfr(const std::vector<std::string>& sets) {
  return load_case(test::source_dir() / "cases" / "lfr.toml", sets);
}

CaseError override_error(const std::vector<std::string>& sets) {
  try {
    lfr(sets);
  } catch (const CaseError& e) {
    return e;
  }
  ADD_FAILURE() << "no CaseError";
  return CaseError("", "", "");
}

TEST(Overrides, Number) {
  EXPECT_DOUBLE_EQ(lfr({"particles.dx=0.5"}).particles.dx, 0.5);
  EXPECT_DOUBLE_EQ(lfr({"species.D=1e-1"}).species.D, 0.1);
  EXPECT_DOUBLE_EQ(lfr({"time.t_end=5"}).time.t_end, 5.0);  // integer where a float is expected
  EXPECT_DOUBLE_EQ(lfr({"particles.dx=.5"}).particles.dx, 0.5);  // not TOML, still a number
  EXPECT_DOUBLE_EQ(lfr({" species.k = 2 "}).species.k, 2.0);     // spaces around
}

// particles.skin defaults by flow when neither the file nor --set gives it: 0.2 in prescribed
// flow (lists last several steps), 0.05 otherwise; a given value always wins.
TEST(Overrides, SkinDefaultFollowsTheFlow) {
  const auto dir = test::source_dir() / "cases";
  EXPECT_DOUBLE_EQ(load_case(dir / "default.toml", {}).particles.skin,
                   Case::Particles::kPrescribedSkin);  // prescribed, no skin in the file
  EXPECT_DOUBLE_EQ(load_case(dir / "default.toml", {"flow=wcsph"}).particles.skin, 0.05);
  EXPECT_DOUBLE_EQ(load_case(dir / "default.toml", {"particles.skin=0.1"}).particles.skin, 0.1);
  // lfr.toml sets 0.05 itself: prescribed flow keeps it
  EXPECT_DOUBLE_EQ(lfr({"flow=prescribed"}).particles.skin, 0.05);
}

TEST(Overrides, Integer) {
  EXPECT_EQ(lfr({"time.max_steps=3"}).time.max_steps, 3);
}

TEST(Overrides, BareAndQuotedStrings) {
  EXPECT_EQ(lfr({"scheme=conventional"}).scheme, Scheme::conventional);
  EXPECT_EQ(lfr({"scheme=\"conventional\""}).scheme, Scheme::conventional);
  EXPECT_EQ(lfr({"flow=prescribed"}).flow, Flow::prescribed);
  EXPECT_EQ(lfr({"name=run_42"}).name, "run_42");
  EXPECT_EQ(lfr({"name=2024"}).name, "2024");  // a number where a string is expected: its text
}

TEST(Overrides, Boolean) {
  EXPECT_TRUE(lfr({"species.ale=true"}).species.ale);
  EXPECT_FALSE(lfr({"output.progress=false"}).output.progress);
  EXPECT_FALSE(lfr({"time.stop_when_steady=false"}).time.stop_when_steady);
}

TEST(Overrides, Array) {
  EXPECT_EQ(lfr({"output.field_times=[1, 2.5]"}).output.field_times,
            (std::vector<double>{1.0, 2.5}));
  EXPECT_TRUE(lfr({"output.field_times=[]"}).output.field_times.empty());
}

TEST(Overrides, LaterOverrideWins) {
  EXPECT_DOUBLE_EQ(lfr({"particles.dx=0.5", "particles.dx=0.125"}).particles.dx, 0.125);
}

TEST(Overrides, TheMatrixNeedsNoCopies) {
  for (const char* scheme : {"modern", "conventional"})
    for (const char* dx : {"0.5", "0.25", "0.125"})
      for (const char* D : {"1000", "10", "0.1"}) {
        const Case c = lfr({std::string("scheme=") + scheme, std::string("particles.dx=") + dx,
                            std::string("species.D=") + D});
        EXPECT_STREQ(to_string(c.scheme), scheme);
        EXPECT_DOUBLE_EQ(c.particles.dx, std::stod(dx));
        EXPECT_DOUBLE_EQ(c.species.D, std::stod(D));
      }
}

TEST(Overrides, UnknownKeyNamesSetAndSuggests) {
  const CaseError e = override_error({"species.DD=1"});
  EXPECT_EQ(e.file(), "--set");
  EXPECT_EQ(e.key(), "species.DD");
  EXPECT_THAT(e.what(), HasSubstr("--set"));
  EXPECT_THAT(e.what(), HasSubstr("did you mean 'species.D'?"));
}

TEST(Overrides, MissingEquals) {
  const CaseError e = override_error({"particles.dx"});
  EXPECT_EQ(e.file(), "--set");
  EXPECT_THAT(e.what(), HasSubstr("key=value"));
}

TEST(Overrides, WrongType) {
  const CaseError e = override_error({"particles.dx=fine"});
  EXPECT_EQ(e.key(), "particles.dx");
  EXPECT_THAT(e.what(), HasSubstr("--set"));
  EXPECT_THAT(e.what(), HasSubstr("expected a number"));
}

TEST(Overrides, WrongBoolean) {
  const CaseError e = override_error({"species.ale=yes"});
  EXPECT_THAT(e.what(), HasSubstr("expected a boolean"));
}

TEST(Overrides, BadEnum) {
  const CaseError e = override_error({"scheme=fancy"});
  EXPECT_EQ(e.key(), "scheme");
  EXPECT_THAT(e.what(), HasSubstr("\"modern\" | \"conventional\""));
}

TEST(Overrides, TableIsNotAValue) {
  const CaseError e = override_error({"species=1"});
  EXPECT_EQ(e.key(), "species");
  EXPECT_THAT(e.what(), HasSubstr("table"));
}

TEST(Overrides, InvalidValueIsValidated) {
  const CaseError e = override_error({"species.D=-3"});
  EXPECT_EQ(e.file(), "--set");
  EXPECT_EQ(e.key(), "species.D");
}

}  // namespace
}  // namespace adrsph
