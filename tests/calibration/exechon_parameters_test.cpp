#include "pkm/calibration/exechon_parameters.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/io/machine_loader.hpp"

namespace pkm::calibration {
namespace PKM_TEST_NS {

constexpr double kExact = 1e-12;  // round trips through exp/log, relative to 1

kinematics::ExechonModel model() { return io::loadExechonMachine("mxt700s-like").model; }

TEST(ExechonParameters, NamesRoundTripAndAreUnique) {
  for (int k = 0; k < kExechonParameters; ++k) {
    EXPECT_EQ(exechonParameterIndex(exechonParameterName(k)), k);
    for (int j = 0; j < k; ++j) EXPECT_NE(exechonParameterName(j), exechonParameterName(k));
  }
  EXPECT_EQ(exechonParameterName(0), "tripod.dA");
  EXPECT_EQ(exechonParameterName(kExechonBaseParameter + 5), "base.rz");
  EXPECT_THROW((void)exechonParameterName(kExechonParameters), InvalidArgument);
  EXPECT_THROW((void)exechonParameterIndex("tripod.dD"), InvalidArgument);
  EXPECT_FALSE(exechonParameterIsLength(exechonParameterIndex("wrist.c0")));
  EXPECT_TRUE(exechonParameterIsLength(exechonParameterIndex("wrist.tool_length")));
  EXPECT_TRUE(exechonParameterIsLength(exechonParameterIndex("tripod.l12B")));
  EXPECT_TRUE(exechonParameterIsLength(exechonParameterIndex("tripod.l23B")));
  EXPECT_TRUE(exechonParameterIsLength(exechonParameterIndex("base.z")));
  EXPECT_FALSE(exechonParameterIsLength(exechonParameterIndex("base.ry")));
}

TEST(ExechonParameters, ModelAtItsOwnReferenceHasZeroPlacement) {
  const kinematics::ExechonModel m = model();
  const ExechonParameterVector p = exechonParameters(m, m.world_T_zoppi);
  EXPECT_DOUBLE_EQ(p(0), m.tripod.dA);
  EXPECT_DOUBLE_EQ(p(13), m.tripod.hz);
  EXPECT_DOUBLE_EQ(p(exechonParameterIndex("tripod.l12B")), m.tripod.l12B);
  EXPECT_DOUBLE_EQ(p(kExechonOffsetParameter + 1), m.legs[1].length_offset);
  EXPECT_DOUBLE_EQ(p(kExechonWristParameter + 2), m.wrist.tool_length);
  EXPECT_NEAR(p.tail<6>().norm(), 0.0, kExact);
}

TEST(ExechonParameters, SetThenGetRoundTrips) {
  const kinematics::ExechonModel m = model();
  ExechonParameterVector p = exechonParameters(m, m.world_T_zoppi);
  for (int k = 0; k < kExechonParameters; ++k) p(k) += 0.01 * (k + 1) * (k % 2 == 0 ? 1 : -1);
  const kinematics::ExechonModel changed = withExechonParameters(m, p, m.world_T_zoppi);
  const ExechonParameterVector back = exechonParameters(changed, m.world_T_zoppi);
  EXPECT_LT((back - p).cwiseAbs().maxCoeff(), kExact * 1e3);
  // The placement correction is a left perturbation: R = exp(δω)·R₀.
  const Eigen::Matrix3d expected =
      geometry::so3Exp(p.segment<3>(kExechonBaseParameter + 3)) * m.world_T_zoppi.linear();
  EXPECT_LT((changed.world_T_zoppi.linear() - expected).norm(), kExact);
  EXPECT_EQ(changed.tripod.delta1B, m.tripod.delta1B);
  EXPECT_EQ(changed.limits.alpha.min, m.limits.alpha.min);
  EXPECT_EQ(changed.tripod.l12B, p(exechonParameterIndex("tripod.l12B")));
  EXPECT_EQ(changed.tripod.l23B, p(exechonParameterIndex("tripod.l23B")));
}

TEST(ExechonParameters, NonFiniteParameterThrows) {
  const kinematics::ExechonModel m = model();
  ExechonParameterVector p = exechonParameters(m, m.world_T_zoppi);
  p(3) = std::nan("");
  EXPECT_THROW((void)withExechonParameters(m, p, m.world_T_zoppi), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration
