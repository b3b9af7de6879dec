// calibration::explainsData and implausibleChanges: the acceptance rules of every calibration.
#include "pkm/calibration/acceptance.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace pkm::calibration {
namespace PKM_TEST_NS {

TEST(ExplainsData, ResidualsBelowAThousandthOfTheMachineAreAccepted) {
  EXPECT_TRUE(explainsData(0.0, 1000.0));
  EXPECT_TRUE(explainsData(0.999, 1000.0));
  EXPECT_FALSE(explainsData(1.0, 1000.0));  // the bound itself is not below it
  EXPECT_FALSE(explainsData(5.0, 1000.0));
  EXPECT_TRUE(explainsData(0.0009, 1.0));  // the same rule for a machine in metres or inches
  EXPECT_FALSE(explainsData(std::numeric_limits<double>::quiet_NaN(), 1000.0));
  EXPECT_FALSE(explainsData(std::numeric_limits<double>::infinity(), 1000.0));
  static_assert(explainsData(0.5, 1000.0) && kAcceptableResidualFraction == 1e-3);
}

TEST(ImplausibleChanges, LengthsAgainstTheMachineSizeAnglesInRadians) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const std::vector<ParameterValues> p = {
      {"base0.x", 100.0, 133.0, true},     // 33 mm on a 1 m platform: plausible
      {"base0.y", 13.25, 680.18, true},    // 666.9 mm: refused
      {"offset3", 0.0, -260.0, true},      // 260 > 250: refused
      {"tripod.rx", 0.0, 0.019, false},    // 0.019 rad: plausible
      {"tripod.ry", 0.0, -0.03, false},    // 0.03 rad: refused
      {"platform1.z", 5.0, nan, true},     // NaN: refused
      {"platform2.z", 5.0, 255.0, true}};  // exactly 250: plausible (the bound is allowed)
  const std::vector<ParameterChange> c = implausibleChanges(p, 1000.0, "mm");
  ASSERT_EQ(c.size(), 4U);
  EXPECT_EQ(c[0].values.name, "platform1.z");  // NaN first, then by change / limit
  EXPECT_EQ(c[1].values.name, "base0.y");
  EXPECT_EQ(c[2].values.name, "tripod.ry");
  EXPECT_EQ(c[3].values.name, "offset3");
  EXPECT_DOUBLE_EQ(c[1].limit, kPlausibleChangeFraction * 1000.0);
  EXPECT_EQ(c[1].unit, "mm");
  EXPECT_EQ(c[2].unit, "rad");
  EXPECT_DOUBLE_EQ(c[3].change(), -260.0);
  EXPECT_EQ(describe(c[1]), "base0.y: 13.25 → 680.18 mm (moved 666.9; plausible ≤ 250)");
  EXPECT_TRUE(implausibleChanges({p[0], p[3]}, 1000.0, "mm").empty());
  EXPECT_EQ(implausibleChanges({p[0]}, 1000.0, "mm", 0.02).size(), 1U);  // a stricter fraction
  EXPECT_EQ(implausibleChanges({p[3]}, 1000.0, "mm", 0.25, 0.01).size(), 1U);  // and angle limit
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration
