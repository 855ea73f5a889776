#include <gtest/gtest.h>

#include "adrsph/case.hpp"

TEST(Smoke, CaseDefaultsArePhysical) {
  adrsph::Case c;
  EXPECT_DOUBLE_EQ(c.u_max(), 200.0);
  EXPECT_DOUBLE_EQ(c.c0(), 2000.0);
  EXPECT_NEAR(c.peclet(), 1000.0, 1e-9);
}
