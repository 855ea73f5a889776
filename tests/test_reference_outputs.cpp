// Reference outputs (issue 4): sampling at probe points, the probe/station contract, the
// HDF5 field and the `adrsph reference` command (coarse grids: fast).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "io_test_util.hpp"
#include "reference_test_util.hpp"

namespace adrsph::reference {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

// A field linear in x and y is sampled exactly between cell centres; walls and outlet use
// the adjacent cell (zero gradient), x < dx/2 the inlet value.
TEST(ReferenceSampling, BilinearWithZeroGradientEdges) {
  Problem p = testing::reactor(10.0);
  Solution s;
  s.grid = Grid{10, 4, 100.0, 5.0};
  s.c.resize(static_cast<std::size_t>(s.grid.cells()));
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 4; ++j)
      s.c[s.grid.index(i, j)] = 1.0 + 0.01 * s.grid.xc(i) + 0.1 * s.grid.yc(j);
  EXPECT_NEAR(sample(s, p, 50.0, 0.0), 1.5, 1e-12);
  EXPECT_NEAR(sample(s, p, 33.0, 1.0), 1.0 + 0.33 + 0.1, 1e-12);
  EXPECT_NEAR(sample(s, p, 100.0, 0.0), 1.0 + 0.95, 1e-12);  // outlet: last centre
  EXPECT_NEAR(sample(s, p, 50.0, 5.0), 1.5 + 0.375, 1e-12);  // wall: last row centre
  EXPECT_NEAR(sample(s, p, 0.0, 0.0), p.c_in, 1e-12);        // inlet: Dirichlet value
  EXPECT_NEAR(sample(s, p, 2.5, 0.0), 0.5 * (p.c_in + 1.05), 1e-12);
  EXPECT_NEAR(section_average(s, p, 50.0), 1.5, 1e-12);
  const ProbeTable t = probe_table(s, p);
  ASSERT_EQ(t.x_mm.size(), 200u);
  EXPECT_NEAR(t.c_yp25[99], 1.5 + 0.25, 1e-12);  // x = 50, y = +2.5
  EXPECT_NEAR(t.c_ym25[99], 1.5 - 0.25, 1e-12);
  const StationTable st = station_table(s, p);
  EXPECT_NEAR(st.c_mean[0], 1.25, 1e-12);
}

// Symmetry of the reactor: the y = +2.5 and -2.5 lines agree.
TEST(ReferenceSampling, ReactorIsSymmetric) {
  const Problem p = testing::reactor(10.0);
  const Solution s = solve_steady(p, 200, 20);
  const ProbeTable t = probe_table(s, p);
  for (std::size_t i = 0; i < t.x_mm.size(); ++i)
    EXPECT_NEAR(t.c_yp25[i], t.c_ym25[i], 1e-12 * t.c_y0[i]);
}

TEST(ReferenceOutputs, Hdf5FieldRoundTrip) {
  test::TempDir dir;
  const Problem p = testing::reactor(10.0);
  const Solution s = solve_steady(p, 40, 8);
  write_reference_h5(dir / "reference.h5", s, p);
  const ReferenceField f = read_reference_h5(dir / "reference.h5");
  EXPECT_EQ(f.nx, 40);
  EXPECT_EQ(f.ny, 8);
  ASSERT_EQ(f.c.size(), 320u);
  EXPECT_DOUBLE_EQ(f.c[3 * 40 + 7], s.at(7, 3));  // C[j][i]: ny x nx
  EXPECT_DOUBLE_EQ(f.x[0], 1.25);
  EXPECT_DOUBLE_EQ(f.y[0], -4.375);
  EXPECT_DOUBLE_EQ(f.D, 10.0);
  EXPECT_DOUBLE_EQ(f.k, 1.462);
  EXPECT_DOUBLE_EQ(f.u_bulk, 100.0);
  EXPECT_THROW(read_reference_h5(dir / "missing.h5"), std::runtime_error);
}

std::string lfr_case() {
  std::string s(1, '\'');
  s += (test::source_dir() / "cases" / "lfr.toml").string();
  s += '\'';
  return s;
}

TEST(ReferenceCli, WritesTheFourFiles) {
  test::TempDir dir;
  const auto r = test::run_adrsph(
      "reference " + lfr_case() + " --set species.D=10 --nx 200 --ny 20 --out ref", dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"probes.csv", "stations.csv", "reference.h5", "reference.json"})
    EXPECT_TRUE(fs::exists(dir / "ref" / f)) << f;
  EXPECT_EQ(read_probes_csv(dir / "ref" / "probes.csv").x_mm.size(), 200u);
  const StationTable st = read_stations_csv(dir / "ref" / "stations.csv");
  EXPECT_NEAR(st.c_mean[2], 0.6644, 2e-3);  // Pe = 1000 outlet (1600x160: 0.66436)
  const std::string json = test::read_file(dir / "ref" / "reference.json");
  EXPECT_THAT(json, HasSubstr("\"nx\": 200"));
  EXPECT_THAT(json, HasSubstr("\"Pe\": 1000"));
  EXPECT_THAT(json, HasSubstr("\"converged\": true"));
}

TEST(ReferenceCli, ConvergenceTablePrintsOrdersAndVerdict) {
  test::TempDir dir;
  const auto r = test::run_adrsph(
      "reference " + lfr_case() + " --set species.D=10 --nx 160 --ny 16 --convergence --out c",
      dir.path());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("| 40x4 |"));
  EXPECT_THAT(r.out, HasSubstr("| 320x32 |"));
  EXPECT_THAT(r.out, HasSubstr("order p"));
  EXPECT_THAT(r.out, HasSubstr("from 160x16 to 320x32"));
  EXPECT_TRUE(fs::exists(dir / "c" / "convergence.md"));
  EXPECT_TRUE(fs::exists(dir / "c" / "stations.csv"));
}

TEST(ReferenceCli, BadInputExits2NamingTheKey) {
  test::TempDir dir;
  auto r = test::run_adrsph("reference " + lfr_case() + " --set species.D=-1", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("species.D"));
  r = test::run_adrsph("reference missing.toml", dir.path());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("missing.toml"));
  r = test::run_adrsph("reference " + lfr_case() + " --nx 1", dir.path());
  EXPECT_EQ(r.exit_code, 2);
}

}  // namespace
}  // namespace adrsph::reference
