// The true hexapod behind a controller's joint commands (pkm/simulation/machine_in_loop.hpp):
// without errors the sensors read the commanded motion; with assembly errors the true pose is the
// true model's forward kinematics of the commanded readings; zeroing, the laser, a command that
// cannot be followed, backlash on reversal.
#include "pkm/simulation/machine_in_loop.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "pkm/core/units.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/sample_models.hpp"

namespace pkm::simulation {
namespace PKM_TEST_NS {

namespace kin = pkm::kinematics;
constexpr double kTol = 1e-7;  // mm: forward kinematics converge to 1e-9 mm

/// The nominal readings of `pose` (x y z mm, a b c degrees).
kin::StrutVector readings(const kin::HexapodModel& m, std::array<double, 6> pose) {
  kin::HexapodData data(m);
  kin::PoseRpy p;
  p.position = {pose[0], pose[1], pose[2]};
  p.rpy = {degToRad(pose[3]), degToRad(pose[4]), degToRad(pose[5])};
  return kin::inverseKinematics(m, data, p);
}

HexapodAssemblyErrors someErrors() {
  HexapodAssemblyErrors e;
  for (std::size_t i = 0; i < 6; ++i) {
    const double s = static_cast<double>(i) - 2.5;
    e.base_joint[i] = {3 * s, -2 * s, s};
    e.platform_joint[i] = {-s, 1.5 * s, 0.5};
    e.length_offset[static_cast<Eigen::Index>(i)] = 2 * s;
  }
  return e;
}

TEST(HexapodMachineInLoop, WithoutErrorsTheSensorsReadTheCommandedMotion) {
  const kin::HexapodModel m = pkm::test::millingModel();
  HexapodMachineInLoop loop(HexapodVirtualMachine(m, HexapodAssemblyErrors{}));
  ASSERT_TRUE(loop.command(readings(m, {0, 0, 200, 0, 0, 0})));
  for (const double g : loop.gauges()) EXPECT_NEAR(g, 0.0, kTol);   // zeroed at the first command
  ASSERT_TRUE(loop.command(readings(m, {40, -25, 200, 0, 0, 7})));  // in the table plane
  for (const double g : loop.gauges()) EXPECT_NEAR(g, 0.0, kTol);
  EXPECT_NEAR(loop.laser(), 40.0, kTol);
  ASSERT_TRUE(loop.command(readings(m, {40, -25, 212.5, 0, 0, 7})));  // up
  for (const double g : loop.gauges()) EXPECT_NEAR(g, 12.5, kTol);
  EXPECT_NEAR(loop.truePose().translation().z(), 212.5, kTol);
  loop.zero();
  for (const double g : loop.gauges()) EXPECT_EQ(g, 0.0);
  EXPECT_EQ(loop.laser(), 0.0);
}

TEST(HexapodMachineInLoop, TheTruePoseIsTheTrueModelsForwardKinematics) {
  const kin::HexapodModel m = pkm::test::millingModel();
  const HexapodAssemblyErrors errors = someErrors();
  HexapodMachineInLoop loop(HexapodVirtualMachine(m, errors));
  const kin::HexapodModel truth = errors.apply(m);
  for (const auto& pose :
       {std::array<double, 6>{0, 0, 200, 0, 0, 0}, std::array<double, 6>{30, 20, 190, 2, -3, 10}}) {
    const kin::StrutVector q = readings(m, pose);
    ASSERT_TRUE(loop.command(q));
    kin::HexapodData data(truth);
    kin::PoseRpy seed;
    seed.position = {pose[0], pose[1], pose[2]};
    ASSERT_TRUE(kin::forwardKinematics(truth, data, q, seed).ok());
    EXPECT_LT((loop.truePose().translation() - data.pose.position).norm(), kTol);
    EXPECT_LT((loop.truePose().linear() - data.world_R_platform).norm(), 1e-9);
    EXPECT_LT((loop.commandedPose().position - Eigen::Vector3d(pose[0], pose[1], pose[2])).norm(),
              kTol);
  }
}

TEST(HexapodMachineInLoop, ACommandItCannotFollowKeepsThePose) {
  const kin::HexapodModel m = pkm::test::millingModel();
  HexapodMachineInLoop loop(HexapodVirtualMachine(m, HexapodAssemblyErrors{}));
  ASSERT_TRUE(loop.command(readings(m, {0, 0, 200, 0, 0, 0})));
  const Eigen::Vector3d before = loop.truePose().translation();
  EXPECT_FALSE(loop.command(kin::StrutVector::Constant(-1000)));  // joint distances < 0
  EXPECT_EQ(loop.truePose().translation(), before);
}

TEST(HexapodMachineInLoop, AFarJumpIsSolvedFromHome) {
  // A controller's joints before homing (all readings 0), then at home.
  const kin::HexapodModel m = pkm::test::millingModel();
  HexapodMachineInLoop loop(HexapodVirtualMachine(m, someErrors()));
  ASSERT_TRUE(loop.command(kin::StrutVector::Zero()));
  ASSERT_TRUE(loop.command(readings(m, {0, 0, 200, 0, 0, 0})));
  EXPECT_LT((loop.commandedPose().position - Eigen::Vector3d(0, 0, 200)).norm(), kTol);
  EXPECT_LT(std::abs(loop.truePose().translation().z() - 200), 20.0);
}

TEST(HexapodMachineInLoop, BacklashShowsWhenAStrutReverses) {
  const kin::HexapodModel m = pkm::test::millingModel();
  StrutActuation act;
  act.backlash = kin::StrutVector::Constant(0.02);
  HexapodMachineInLoop loop(HexapodVirtualMachine(m, HexapodAssemblyErrors{}, act));
  // Servo steps of 0.25 mm (a jump of a reading over 1 mm restarts the machine).
  const auto rampTo = [&](double from, double to) {
    const int n = static_cast<int>(std::abs(to - from) / 0.25);
    for (int k = 1; k <= n; ++k)
      ASSERT_TRUE(loop.command(readings(m, {0, 0, from + (to - from) * k / n, 0, 0, 0})));
  };
  ASSERT_TRUE(loop.command(readings(m, {0, 0, 190, 0, 0, 0})));
  rampTo(190, 200);  // down: the struts lengthen
  const double from_below = loop.truePose().translation().z();
  rampTo(200, 210);
  rampTo(210, 200);  // up: the struts shorten
  const double from_above = loop.truePose().translation().z();
  EXPECT_GT(std::abs(from_above - from_below), 0.01);  // about the backlash, projected
}

TEST(LoopSensors, CollinearGaugesAreRefused) {
  LoopSensors s;
  s.gauge_points = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(2, 0, 0)};
  EXPECT_THROW(s.validate(), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::simulation
