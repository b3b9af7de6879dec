#include "pkm/core/units.hpp"

#include <gtest/gtest.h>

#include "support/tolerances.hpp"

namespace pkm {
namespace PKM_TEST_NS {

TEST(Units, LengthUnitStringsRoundTrip) {
  for (LengthUnit u : {LengthUnit::kMillimetre, LengthUnit::kInch}) {
    EXPECT_EQ(lengthUnitFromString(toString(u)), u);
  }
  EXPECT_EQ(lengthUnitFromString("in"), LengthUnit::kInch);
  EXPECT_FALSE(lengthUnitFromString("m").has_value());
  EXPECT_FALSE(lengthUnitFromString("").has_value());
}

TEST(Units, MillimetresPerUnit) {
  EXPECT_EQ(millimetresPer(LengthUnit::kMillimetre), 1.0);
  EXPECT_EQ(millimetresPer(LengthUnit::kInch), 25.4);
}

TEST(Units, AngleConversions) {
  EXPECT_NEAR(degToRad(180.0), std::numbers::pi, test::kTolExact);
  EXPECT_NEAR(radToDeg(std::numbers::pi / 2), 90.0, test::kTolExact);
  EXPECT_NEAR(radToDeg(degToRad(37.25)), 37.25, test::kTolExact);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm
