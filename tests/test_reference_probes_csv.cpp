// The probe contract (include/adrsph/probes.hpp): exact headers, full precision round trip,
// readers that name the file and the line.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "adrsph/probes.hpp"
#include "io_test_util.hpp"

namespace adrsph {
namespace {

using ::testing::HasSubstr;

TEST(ProbesCsv, PositionsFollowTheSpec) {
  const auto x = probe_x_positions(100.0);
  ASSERT_EQ(x.size(), 200u);
  EXPECT_DOUBLE_EQ(x.front(), 0.5);
  EXPECT_DOUBLE_EQ(x[1], 1.0);
  EXPECT_DOUBLE_EQ(x.back(), 100.0);
  EXPECT_EQ(station_x_positions(100.0), (std::vector<double>{25.0, 50.0, 100.0}));
  EXPECT_EQ(station_x_positions(50.0), (std::vector<double>{12.5, 25.0, 50.0}));
}

TEST(ProbesCsv, RoundTripKeepsTenSignificantDigits) {
  test::TempDir dir;
  ProbeTable t;
  t.x_mm = {0.5, 1.0, 100.0};
  t.c_y0 = {1.9876543210987, 1.5, 0.123456789012};
  t.c_yp25 = {1.1, 1.2, 1.3};
  t.c_ym25 = {2.0, 1e-7, 0.0};
  t.c_mean = {1.0 / 3.0, 2.0 / 3.0, 0.62800};
  write_probes_csv(dir / "probes.csv", t);
  const std::string text = test::read_file(dir / "probes.csv");
  EXPECT_EQ(text.substr(0, text.find('\n')), "x_mm,C_y0,C_y+2.5,C_y-2.5,C_mean");
  const ProbeTable r = read_probes_csv(dir / "probes.csv");
  ASSERT_EQ(r.x_mm.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(r.x_mm[i], t.x_mm[i]);
    EXPECT_NEAR(r.c_y0[i], t.c_y0[i], 5e-10 * std::abs(t.c_y0[i]));
    EXPECT_NEAR(r.c_yp25[i], t.c_yp25[i], 5e-10 * std::abs(t.c_yp25[i]));
    EXPECT_NEAR(r.c_ym25[i], t.c_ym25[i], 5e-10 * std::abs(t.c_ym25[i]));
    EXPECT_NEAR(r.c_mean[i], t.c_mean[i], 5e-10 * std::abs(t.c_mean[i]));
  }

  StationTable s{{25.0, 50.0, 100.0}, {1.38274, 1.04125, 0.628}};
  write_stations_csv(dir / "stations.csv", s);
  EXPECT_EQ(test::read_file(dir / "stations.csv"),
            "x_mm,C_mean\n25,1.38274\n50,1.04125\n100,0.628\n");
  const StationTable rs = read_stations_csv(dir / "stations.csv");
  EXPECT_EQ(rs.x_mm, s.x_mm);
  EXPECT_EQ(rs.c_mean, s.c_mean);
}

void expect_read_error(const std::string& text, const std::string& line_tag,
                       const std::string& what) {
  test::TempDir dir;
  test::write_file(dir / "stations.csv", text);
  try {
    read_stations_csv(dir / "stations.csv");
    ADD_FAILURE() << "no error for: " << text;
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("stations.csv:" + line_tag));
    EXPECT_THAT(e.what(), HasSubstr(what));
  }
}

TEST(ProbesCsv, ReadersNameFileAndLine) {
  expect_read_error("x,C\n25,1\n", "1", "expected header");
  expect_read_error("x_mm,C_mean\n25,1.0\n50,abc\n", "3", "not a number");
  expect_read_error("x_mm,C_mean\n25,1.0,3\n", "2", "expected 2 fields");
  expect_read_error("x_mm,C_mean\n25,nan\n", "2", "non-finite");
  expect_read_error("x_mm,C_mean\n25,1.0x\n", "2", "not a number");
  expect_read_error("", "0", "empty file");
  EXPECT_THROW(read_probes_csv("/nonexistent/probes.csv"), std::runtime_error);
}

TEST(ProbesCsv, ToleratesCrLfAndBlankLines) {
  test::TempDir dir;
  test::write_file(dir / "stations.csv", "x_mm,C_mean\r\n25,1.5\r\n\r\n50,1.25\r\n");
  const StationTable t = read_stations_csv(dir / "stations.csv");
  EXPECT_EQ(t.c_mean, (std::vector<double>{1.5, 1.25}));
}

}  // namespace
}  // namespace adrsph
