#include "pkm/calibration/hexapod_parameters.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <set>

#include "pkm/core/error.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace pkm::calibration {
namespace PKM_TEST_NS {

TEST(HexapodParameters, RoundTripThroughTheModel) {
  const kinematics::HexapodModel model = test::millingModel();
  HexapodParameterVector p = hexapodParameters(model);
  EXPECT_EQ(p(baseParameter(2, 1)), model.struts[2].world_p_base.y());
  EXPECT_EQ(p(platformParameter(4, 0)), model.struts[4].platform_p_joint.x());
  EXPECT_EQ(p(offsetParameter(5)), model.struts[5].length_offset);
  p(platformParameter(1, 2)) += 0.25;
  const kinematics::HexapodModel changed = withHexapodParameters(model, p);
  EXPECT_EQ(changed.struts[1].platform_p_joint.z(), model.struts[1].platform_p_joint.z() + 0.25);
  EXPECT_EQ(changed.tool_offset, model.tool_offset);  // not a parameter
  EXPECT_EQ(hexapodParameters(changed), p);
}

TEST(HexapodParameters, NamesAreUniqueAndInvertible) {
  std::set<std::string> names;
  for (int k = 0; k < kHexapodParameters; ++k) {
    const std::string name = hexapodParameterName(k);
    EXPECT_TRUE(names.insert(name).second) << name;
    EXPECT_EQ(hexapodParameterIndex(name), k);
  }
  EXPECT_EQ(hexapodParameterName(baseParameter(0, 0)), "base0.x");
  EXPECT_EQ(hexapodParameterName(platformParameter(3, 2)), "platform3.z");
  EXPECT_EQ(hexapodParameterName(offsetParameter(5)), "offset5");
  EXPECT_THROW((void)hexapodParameterName(42), InvalidArgument);
  EXPECT_THROW((void)hexapodParameterIndex("base6.x"), InvalidArgument);
}

TEST(HexapodParameters, RejectsNonFiniteValues) {
  HexapodParameterVector p = hexapodParameters(test::millingModel());
  p(7) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)withHexapodParameters(test::millingModel(), p), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration
