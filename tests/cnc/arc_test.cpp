// Arc centres: IJK radius check, R format incl. the sign rule for arcs over 180 degrees.
#include "pkm/cnc/arc.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "pkm/cnc/gcode_error.hpp"
#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace pkm::cnc {
namespace PKM_TEST_NS {

using pkm::test::kTolRoundTrip;

constexpr double kMm = ArcTolerances::kDefaultMm;  // t of a G21 program, mm

TEST(Arc, CentreFormatKeepsTheCentre) {
  const ArcCentre a = arcFromCentre(0, 0, 10, 0, 5, 0, kMm);
  EXPECT_EQ(a.c1, 5.0);
  EXPECT_EQ(a.c2, 0.0);
  EXPECT_EQ(a.radius, 5.0);
}

// The limits of LinuxCNC 2.9's rule, each approached from both sides (e = |r1 - r2|,
// t = 2·0.01·√2 mm = 0.028284 mm): e ≤ t passes whatever the relative error; e > t passes while
// e / max(r1, r2) ≤ 0.1 %; e > 100 t never passes.
TEST(Arc, CentreFormatRadiusRuleAtItsLimits) {
  const double t = kMm;
  // Radius 1: relative error far above 0.1 %, so t decides (centre moved by e/2 on the chord).
  EXPECT_NO_THROW(arcFromCentre(0, 0, 2, 0, 1 - 0.49 * t, 0, t));
  EXPECT_THROW(arcFromCentre(0, 0, 2, 0, 1 - 0.51 * t, 0, t), GcodeError);
  // Radius 1000: e = 0.9995 mm is 0.0999 % of the larger radius; e = 1.0005 mm is 0.1 % + .
  EXPECT_NO_THROW(arcFromCentre(0, 0, 2000, 0, 999.50025, 0, t));
  EXPECT_THROW(arcFromCentre(0, 0, 2000, 0, 999.4995, 0, t), GcodeError);
  // Radius 3000: 0.0952 % passes the relative test but e is just over 100 t.
  EXPECT_NO_THROW(arcFromCentre(0, 0, 6000, 0, 3000 + 49.9 * t, 0, t));
  EXPECT_THROW(arcFromCentre(0, 0, 6000, 0, 3000 + 50.1 * t, 0, t), GcodeError);
  // G20: t = 2·0.001·√2 in = 0.0718 mm.
  const double ti = ArcTolerances{}.centreMm(true);
  EXPECT_NEAR(ti, 0.0718420, 1e-6);
  EXPECT_NO_THROW(arcFromCentre(0, 0, 2, 0, 1 - 0.49 * ti, 0, ti));
  EXPECT_THROW(arcFromCentre(0, 0, 2, 0, 1 - 0.51 * ti, 0, ti), GcodeError);
  // Zero radius: below 0.00127 mm at either end.
  EXPECT_THROW(arcFromCentre(0, 0, 1, 1, 0, 0, t), GcodeError);
  EXPECT_THROW(arcFromCentre(0, 0, 0.0024, 0, 0.0012, 0, t), GcodeError);
  EXPECT_NO_THROW(arcFromCentre(0, 0, 0.0026, 0, 0.0013, 0, t));
}

TEST(Arc, IniTolerancesAreBounded) {
  ArcTolerances a;
  EXPECT_NO_THROW(a.validate());
  a.centre_mm = 0.001;
  EXPECT_NO_THROW(a.validate());
  a.centre_mm = 0.0009;
  EXPECT_THROW(a.validate(), InvalidArgument);
  a.centre_mm = 0.03;
  EXPECT_THROW(a.validate(), InvalidArgument);
  a = ArcTolerances{};
  a.centre_inch = 0.00003;
  EXPECT_THROW(a.validate(), InvalidArgument);
}

TEST(Arc, RadiusFormatSignRule) {
  // LinuxCNC docs / rs274: G3 X0 Y10 R-7.0710678 from the origin has its centre at (5, 5).
  const ArcCentre big = arcFromRadius(0, 0, 0, 10, -7.0710678, false);
  EXPECT_NEAR(big.c1, 5.0, 1e-6);
  EXPECT_NEAR(big.c2, 5.0, 1e-6);
  const ArcCentre small = arcFromRadius(0, 0, 0, 10, 7.0710678, false);
  EXPECT_NEAR(small.c1, -5.0, 1e-6);
  EXPECT_NEAR(small.c2, 5.0, 1e-6);
  // G2 mirrors G3.
  const ArcCentre cw = arcFromRadius(0, 0, 0, 10, 7.0710678, true);
  EXPECT_NEAR(cw.c1, 5.0, 1e-6);
  // Half circle: centre on the chord midpoint.
  const ArcCentre half = arcFromRadius(0, 0, 10, 0, 5, true);
  EXPECT_NEAR(half.c1, 5.0, kTolRoundTrip);
  EXPECT_NEAR(half.c2, 0.0, kTolRoundTrip);
}

TEST(Arc, RadiusFormatCentreIsEquidistant) {
  const ArcCentre a = arcFromRadius(1, 2, 7, -3, 12, false);
  EXPECT_NEAR(std::hypot(1 - a.c1, 2 - a.c2), 12.0, kTolRoundTrip);
  EXPECT_NEAR(std::hypot(7 - a.c1, -3 - a.c2), 12.0, kTolRoundTrip);
}

TEST(Arc, RadiusFormatErrors) {
  EXPECT_THROW(arcFromRadius(0, 0, 0, 0, 5, true), GcodeError);        // full circle
  EXPECT_THROW(arcFromRadius(0, 0, 10, 0, 4.9986, true), GcodeError);  // short by 0.0014
  EXPECT_NO_THROW(arcFromRadius(0, 0, 10, 0, 4.9988, true));           // short by 0.0012
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
