#include "pkm/kinematics/hexapod_model.hpp"

#include <gtest/gtest.h>

#include "pkm/core/error.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace pkm::kinematics {
namespace PKM_TEST_NS {

TEST(HexapodModel, SampleModelsValidate) {
  EXPECT_NO_THROW(test::linuxcncSimModel().validate());
  EXPECT_NO_THROW(test::millingModel().validate());
}

TEST(HexapodModel, EffectivePointsIncludeOffsets) {
  HexapodModel m = test::millingModel();
  m.spindle_offset = 3.0;
  const Eigen::Vector3d a = m.struts[2].platform_p_joint, b = m.struts[2].world_p_base;
  EXPECT_LT((m.effectiveBase(2) - (b + Eigen::Vector3d(0, 0, 3))).norm(), test::kTolExact);
  EXPECT_LT((m.effectivePlatform(2) - (a - m.tool_offset + Eigen::Vector3d(0, 0, 3))).norm(),
            test::kTolExact);
}

TEST(HexapodModel, CharacteristicLengthIsMeanPlatformRadius) {
  EXPECT_NEAR(test::millingModel().characteristicLength(), 250.0, 1e-9);
}

TEST(HexapodModel, RejectsNonFiniteGeometry) {
  HexapodModel m = test::millingModel();
  m.struts[3].world_p_base.x() = NAN;
  EXPECT_THROW(m.validate(), InvalidArgument);
  m = test::millingModel();
  m.tool_offset.z() = INFINITY;
  EXPECT_THROW(m.validate(), InvalidArgument);
}

TEST(HexapodModel, RejectsDuplicateLeg) {
  HexapodModel m = test::millingModel();
  m.struts[4] = m.struts[1];
  EXPECT_THROW(m.validate(), InvalidArgument);
}

TEST(HexapodModel, RejectsEmptyStroke) {
  HexapodModel m = test::millingModel();
  m.struts[0].min_reading = 10;
  m.struts[0].max_reading = 5;
  EXPECT_THROW(m.validate(), InvalidArgument);
}

TEST(HexapodModel, RejectsZeroLengthStrutAtHome) {
  HexapodModel m = test::millingModel();
  m.home.position =
      m.struts[0].world_p_base - m.struts[0].platform_p_joint + m.tool_offset;  // joint 0 on base 0
  EXPECT_THROW(m.validate(), InvalidArgument);
}

TEST(HexapodModel, RejectsSingularGeometry) {
  HexapodModel m = test::linuxcncSimModel();
  m.home.position.z() = 0.0;  // platform in the base plane: every strut horizontal
  EXPECT_THROW(m.validate(), InvalidArgument);
  m = test::millingModel();
  for (std::size_t i = 0; i < m.struts.size(); ++i)  // all platform joints on one line
    m.struts[i].platform_p_joint = Eigen::Vector3d(10.0 * static_cast<double>(i), 0, 0);
  EXPECT_THROW(m.validate(), InvalidArgument);
}

TEST(HexapodModel, RejectsBadLimits) {
  HexapodModel m = test::millingModel();
  m.strut_diameter = -1;
  EXPECT_THROW(m.validate(), InvalidArgument);
  m = test::millingModel();
  m.max_condition = 0.5;
  EXPECT_THROW(m.validate(), InvalidArgument);
  m = test::millingModel();
  m.struts[1].base_cone.axis.setZero();
  EXPECT_THROW(m.validate(), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::kinematics
