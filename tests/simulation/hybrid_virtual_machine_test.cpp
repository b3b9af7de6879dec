// HybridVirtualMachine: the hybrid error chain behind the VirtualMachine interface.
#include "pkm/simulation/hybrid_virtual_machine.hpp"

#include <gtest/gtest.h>

#include "pkm/core/error.hpp"
#include "pkm/kinematics/hybrid_chain.hpp"
#include "support/hybrid_samples.hpp"
#include "support/tolerances.hpp"

namespace {

namespace kin = pkm::kinematics;
using pkm::simulation::HybridVirtualMachine;

TEST(HybridVirtualMachine, MatchesTheHybridChain) {
  kin::GeometricErrors errors;
  errors.squareness = {-0.034e-3, -14.74e-3, 4.35e-3, -2.85e-3};
  const kin::HybridMachineModel model = pkm::test::mxt700sLikeModel();
  HybridVirtualMachine m(model, errors);
  EXPECT_EQ(m.axisNames().size(), 5U);
  Eigen::VectorXd c(5);
  c << 400, 100, 10, -50, 30;
  kin::HybridCommand hc;
  hc.x2 = 400;
  hc.y2 = 100;
  hc.pkm = {10, -50, 30};
  EXPECT_TRUE(m.moveTo(c).matrix() == kin::hybridActualPose(model, errors, hc).matrix());
  EXPECT_TRUE(m.nominalPose(c).matrix() == kin::hybridNominalPose(model, hc).matrix());
  EXPECT_THROW((void)m.moveTo(Eigen::VectorXd::Zero(3)), pkm::InvalidArgument);
}

TEST(HybridVirtualMachine, NoErrorsGivesTheNominalPose) {
  HybridVirtualMachine m(pkm::test::mxt700sLikeModel(), {});
  Eigen::VectorXd c(5);
  c << 875, 350, -20, 40, 210;
  EXPECT_NEAR((m.moveTo(c).matrix() - m.nominalPose(c).matrix()).norm(), 0.0, pkm::test::kTolExact);
}

TEST(HybridVirtualMachine, RefusesAMachineInInch) {
  kin::HybridMachineModel model = pkm::test::mxt700sLikeModel();
  model.unit = pkm::LengthUnit::kInch;
  EXPECT_THROW(HybridVirtualMachine(model, {}), pkm::InvalidArgument);
}

}  // namespace
