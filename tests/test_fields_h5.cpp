// HDF5 fields: write synthetic frames, read them back, and the XDMF sidecar.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "adrsph/io/fields_h5.hpp"
#include "io_test_util.hpp"

namespace adrsph {
namespace {

using ::testing::HasSubstr;

struct Arrays {
  std::vector<double> x, y, vx, vy, rho, p, c;
  std::vector<std::uint8_t> kind;

  explicit Arrays(std::size_t n, double shift) {
    for (std::size_t i = 0; i < n; ++i) {
      const double s = static_cast<double>(i) + shift;
      x.push_back(0.5 * s);
      y.push_back(-5.0 + 0.1 * s);
      vx.push_back(200.0 - s);
      vy.push_back(1e-3 * s);
      rho.push_back(1.2 + 1e-6 * s);
      p.push_back(-3.0 + s);
      c.push_back(2.0 / (1.0 + s));
      kind.push_back(static_cast<std::uint8_t>(i % 4));
    }
  }
  FieldFrame frame(double t, long step) const {
    return FieldFrame{t, step, x, y, vx, vy, rho, p, c, kind, {}};
  }
};

TEST(FieldsH5, RoundTrip) {
  test::TempDir dir;
  const auto file = dir / "fields.h5";
  const Arrays a(17, 0.0), b(5, 0.25);
  {
    FieldsWriter w(file);
    w.write(a.frame(0.5, 100));
    w.write(b.frame(1.25, 250));
    ASSERT_EQ(w.frames().size(), 2u);
    EXPECT_EQ(w.frames()[1].n, 5u);
  }
  ASSERT_EQ(count_field_frames(file), 2u);
  const FieldData d0 = read_field_frame(file, 0);
  EXPECT_DOUBLE_EQ(d0.t, 0.5);
  EXPECT_EQ(d0.step, 100);
  EXPECT_EQ(d0.x, a.x);
  EXPECT_EQ(d0.y, a.y);
  EXPECT_EQ(d0.vx, a.vx);
  EXPECT_EQ(d0.vy, a.vy);
  EXPECT_EQ(d0.rho, a.rho);
  EXPECT_EQ(d0.p, a.p);
  EXPECT_EQ(d0.c, a.c);
  EXPECT_EQ(d0.kind, a.kind);
  const FieldData d1 = read_field_frame(file, 1);
  EXPECT_DOUBLE_EQ(d1.t, 1.25);
  EXPECT_EQ(d1.step, 250);
  EXPECT_EQ(d1.c, b.c);
  EXPECT_EQ(d1.kind, b.kind);
}

TEST(FieldsH5, EmptyFrame) {
  test::TempDir dir;
  const Arrays none(0, 0.0);
  {
    FieldsWriter w(dir / "f.h5");
    w.write(none.frame(0.0, 0));
  }
  EXPECT_TRUE(read_field_frame(dir / "f.h5", 0).x.empty());
}

TEST(FieldsH5, FrameNames) {
  EXPECT_EQ(field_frame_name(0), "frame_000000");
  EXPECT_EQ(field_frame_name(42), "frame_000042");
}

TEST(FieldsH5, MismatchedArraysAreRejected) {
  test::TempDir dir;
  Arrays a(4, 0.0);
  a.c.pop_back();
  FieldsWriter w(dir / "f.h5");
  try {
    w.write(a.frame(0.0, 0));
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("f.h5"));
    EXPECT_THAT(e.what(), HasSubstr("array c"));
  }
}

TEST(FieldsH5, ErrorsNameTheFile) {
  test::TempDir dir;
  const auto missing = dir / "missing.h5";
  try {
    read_field_frame(missing, 0);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr(missing.string()));
  }
  {
    const Arrays a(3, 0.0);
    FieldsWriter w(dir / "one.h5");
    w.write(a.frame(0.0, 0));
  }
  EXPECT_THROW(read_field_frame(dir / "one.h5", 1), std::runtime_error);
  EXPECT_THROW(FieldsWriter(dir / "no_such_dir" / "x.h5"), std::runtime_error);
}

TEST(FieldsH5, XdmfSidecar) {
  test::TempDir dir;
  const std::vector<FieldFrameInfo> frames{{0.5, 10, 17}, {1.0, 20, 19}};
  write_fields_xdmf(dir / "fields.xmf", "fields.h5", frames);
  const std::string x = test::read_file(dir / "fields.xmf");
  EXPECT_THAT(x, HasSubstr("CollectionType=\"Temporal\""));
  EXPECT_THAT(x, HasSubstr("TopologyType=\"Polyvertex\""));
  EXPECT_THAT(x, HasSubstr("GeometryType=\"X_Y\""));
  EXPECT_THAT(x, HasSubstr("<Time Value=\"0.5\" />"));
  EXPECT_THAT(x, HasSubstr("fields.h5:/frame_000001/c"));
  EXPECT_THAT(x, HasSubstr("Dimensions=\"19\""));
  for (const char* name : {"vx", "vy", "rho", "p", "c", "kind"})
    EXPECT_THAT(x, HasSubstr(std::string("Attribute Name=\"") + name + "\""));
}

}  // namespace
}  // namespace adrsph
