// Arc centres: IJK radius check, R format incl. the sign rule for arcs over 180 degrees.
#include "pkm/cnc/arc.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "pkm/cnc/gcode_error.hpp"
#include "support/tolerances.hpp"

namespace pkm::cnc {
namespace {

using pkm::test::kTolRoundTrip;

TEST(Arc, CentreFormatKeepsTheCentre) {
  const ArcCentre a = arcFromCentre(0, 0, 10, 0, 5, 0, false);
  EXPECT_EQ(a.c1, 5.0);
  EXPECT_EQ(a.c2, 0.0);
  EXPECT_EQ(a.radius, 5.0);
}

TEST(Arc, CentreFormatRadiusRule) {
  // 0.004 mm differ: below the 0.005 mm floor, accepted whatever the relative error.
  EXPECT_NO_THROW(arcFromCentre(0, 0, 2.004, 0, 1, 0, false));
  // 0.4 mm on a 1000 mm radius: above 0.005 mm but only 0.04 %: accepted.
  EXPECT_NO_THROW(arcFromCentre(0, 0, 2000.4, 0, 1000, 0, false));
  // 0.6 mm: above the 0.5 mm ceiling even on a huge radius.
  EXPECT_THROW(arcFromCentre(0, 0, 20000.6, 0, 10000, 0, false), GcodeError);
  // 0.01 mm on radius 1 (1 %): rejected.
  EXPECT_THROW(arcFromCentre(0, 0, 2.01, 0, 1, 0, false), GcodeError);
  // in G20 the floor is 0.0005 in = 0.0127 mm: 0.01 mm accepted.
  EXPECT_NO_THROW(arcFromCentre(0, 0, 2.01, 0, 1, 0, true));
  EXPECT_THROW(arcFromCentre(0, 0, 1, 1, 0, 0, false), GcodeError);  // zero radius at start
}

TEST(Arc, RadiusFormatSignRule) {
  // LinuxCNC docs / rs274: G3 X0 Y10 R-7.0710678 from the origin has its centre at (5, 5).
  const ArcCentre big = arcFromRadius(0, 0, 0, 10, -7.0710678, false, false);
  EXPECT_NEAR(big.c1, 5.0, 1e-6);
  EXPECT_NEAR(big.c2, 5.0, 1e-6);
  const ArcCentre small = arcFromRadius(0, 0, 0, 10, 7.0710678, false, false);
  EXPECT_NEAR(small.c1, -5.0, 1e-6);
  EXPECT_NEAR(small.c2, 5.0, 1e-6);
  // G2 mirrors G3.
  const ArcCentre cw = arcFromRadius(0, 0, 0, 10, 7.0710678, true, false);
  EXPECT_NEAR(cw.c1, 5.0, 1e-6);
  // Half circle: centre on the chord midpoint.
  const ArcCentre half = arcFromRadius(0, 0, 10, 0, 5, true, false);
  EXPECT_NEAR(half.c1, 5.0, kTolRoundTrip);
  EXPECT_NEAR(half.c2, 0.0, kTolRoundTrip);
}

TEST(Arc, RadiusFormatCentreIsEquidistant) {
  const ArcCentre a = arcFromRadius(1, 2, 7, -3, 12, false, false);
  EXPECT_NEAR(std::hypot(1 - a.c1, 2 - a.c2), 12.0, kTolRoundTrip);
  EXPECT_NEAR(std::hypot(7 - a.c1, -3 - a.c2), 12.0, kTolRoundTrip);
}

TEST(Arc, RadiusFormatErrors) {
  EXPECT_THROW(arcFromRadius(0, 0, 0, 0, 5, true, false), GcodeError);     // full circle
  EXPECT_THROW(arcFromRadius(0, 0, 10, 0, 4.9, true, false), GcodeError);  // too small
  EXPECT_NO_THROW(arcFromRadius(0, 0, 10, 0, 4.996, true, false));         // within 0.005
}

}  // namespace
}  // namespace pkm::cnc
