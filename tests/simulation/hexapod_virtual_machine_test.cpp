// HexapodVirtualMachine: nominal behaviour without errors, a strut length offset with its
// first-order pose error J⁻¹·δ, backlash (hysteresis), repeatability spread, encoder resolution.
#include "pkm/simulation/hexapod_virtual_machine.hpp"

#include <gtest/gtest.h>

#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/sample_models.hpp"
#include "support/statistics.hpp"
#include "support/tolerances.hpp"

namespace {

namespace kin = pkm::kinematics;
namespace sim = pkm::simulation;
using pkm::test::kTolRoundTrip;

constexpr double kOffset = 0.05;  // mm, a strut length offset error
/// First-order models neglect (J⁻¹δ)²/L: 1e-3 of the error is ample.
constexpr double kTolFirstOrder = 1e-3 * kOffset;

Eigen::VectorXd command(double x, double y, double z, double a, double b, double c) {
  Eigen::VectorXd v(6);
  v << x, y, z, a, b, c;
  return v;
}

/// The strut readings of the true model at `pose`.
kin::StrutVector trueReadings(const sim::HexapodVirtualMachine& m,
                              const pkm::geometry::RigidTransform& pose) {
  kin::HexapodData data(m.truth());
  return kin::inverseKinematics(m.truth(), data, pose.translation(), pose.linear());
}

TEST(HexapodVirtualMachine, NoErrorsReachesTheCommand) {
  sim::HexapodVirtualMachine m(pkm::test::millingModel(), {});
  const Eigen::VectorXd c = command(10, -5, 210, 0.03, -0.02, 0.05);
  const pkm::geometry::RigidTransform actual = m.moveTo(c);
  EXPECT_NEAR((actual.matrix() - m.nominalPose(c).matrix()).norm(), 0.0, kTolRoundTrip);
  EXPECT_EQ(m.axisNames().size(), 6U);
}

TEST(HexapodVirtualMachine, LengthOffsetGivesTheFirstOrderPoseError) {
  for (int strut = 0; strut < kin::kStruts; ++strut) {
    sim::HexapodAssemblyErrors e;
    e.length_offset[strut] = kOffset;
    sim::HexapodVirtualMachine m(pkm::test::millingModel(), e);
    const Eigen::VectorXd c = command(5, 8, 195, 0.02, 0.01, -0.03);
    const pkm::geometry::RigidTransform actual = m.moveTo(c);
    const pkm::geometry::RigidTransform nominal = m.nominalPose(c);
    kin::HexapodData data(m.nominal());
    (void)kin::inverseKinematics(m.nominal(), data, nominal.translation(), nominal.linear());
    const kin::Matrix6d& J = kin::computeStrutJacobian(m.nominal(), data);
    // The true strut is longer by the offset for the same reading, so J·δx = δ·e_i.
    const Eigen::Matrix<double, 6, 1> expected =
        J.lu().solve(kOffset * kin::StrutVector::Unit(strut));
    Eigen::Matrix<double, 6, 1> dx;
    dx << actual.translation() - nominal.translation(),
        pkm::geometry::so3Log(actual.linear() * nominal.linear().transpose());
    const double L = m.nominal().characteristicLength();
    EXPECT_NEAR((dx.head<3>() - expected.head<3>()).norm(), 0.0, kTolFirstOrder) << strut;
    EXPECT_NEAR((dx.tail<3>() - expected.tail<3>()).norm() * L, 0.0, kTolFirstOrder) << strut;
  }
}

TEST(HexapodVirtualMachine, StrutGrowthLengthensEveryStrutInProportion) {
  sim::HexapodVirtualMachine m(pkm::test::millingModel(), {});
  const double g = 11.5e-6 * 2.0;  // steel struts 2 K warm
  m.setStrutGrowth(g);
  EXPECT_EQ(m.strutGrowth(), g);
  const Eigen::VectorXd c = command(5, 8, 195, 0.02, 0.01, -0.03);
  const pkm::geometry::RigidTransform actual = m.moveTo(c);
  const kin::StrutVector reached = trueReadings(m, actual);
  for (Eigen::Index i = 0; i < kin::kStruts; ++i) {
    const double joint_distance =
        m.commandedReadings()[i] + m.truth().struts[static_cast<std::size_t>(i)].length_offset;
    EXPECT_NEAR(reached[i] - m.commandedReadings()[i], g * joint_distance, 1e-9) << i;
  }
  // About 23 ppm of a strut of several hundred mm: micrometres at the tool.
  EXPECT_GT((actual.translation() - m.nominalPose(c).translation()).norm(), 1e-3);
  m.setStrutGrowth(0.0);
  EXPECT_NEAR((m.moveTo(c).matrix() - m.nominalPose(c).matrix()).norm(), 0.0, kTolRoundTrip);
  EXPECT_THROW(m.setStrutGrowth(std::nan("")), pkm::InvalidArgument);
}

TEST(HexapodVirtualMachine, BacklashMakesTheApproachDirectionMatter) {
  // A strut that moved in +reading stops b/2 short of its command, one that moved in − b/2 beyond.
  const double b = 0.004;
  sim::StrutActuation act;
  act.backlash = kin::StrutVector::Constant(b);
  sim::HexapodVirtualMachine m(pkm::test::millingModel(), {}, act);
  m.reset(1);
  const Eigen::VectorXd target = command(0, 0, 200, 0, 0, 0);
  pkm::geometry::RigidTransform from[2];
  for (int side = 0; side < 2; ++side) {
    (void)m.moveTo(command(0, 0, side == 0 ? 190 : 210, 0, 0, 0));
    const kin::StrutVector before = m.commandedReadings();
    from[side] = m.moveTo(target);
    const kin::StrutVector error = trueReadings(m, from[side]) - m.commandedReadings();
    for (int i = 0; i < kin::kStruts; ++i) {
      const double sign = m.commandedReadings()[i] > before[i] ? 1.0 : -1.0;
      EXPECT_NEAR(error[i], -0.5 * b * sign, kTolRoundTrip) << side << i;
    }
  }
  // Seed 004 Fig. 6: the same command reached from the two sides gives two poses.
  EXPECT_GT((from[1].translation() - from[0].translation()).norm(), b / 2);
}

TEST(HexapodVirtualMachine, RepeatabilityHasTheSpecifiedSpread) {
  sim::StrutActuation act;
  act.repeatability_sigma = 0.002;
  sim::HexapodVirtualMachine m(pkm::test::millingModel(), {}, act);
  m.reset(pkm::test::kSeed);
  std::vector<double> dev;
  for (int k = 0; k < 300; ++k) {
    const pkm::geometry::RigidTransform pose = m.moveTo(command(0.1 * (k % 7), 0, 200, 0, 0, 0));
    const kin::StrutVector d = trueReadings(m, pose) - m.commandedReadings();
    for (int i = 0; i < kin::kStruts; ++i) dev.push_back(d[i]);
  }
  EXPECT_NEAR(pkm::test::sampleSigma(dev) / act.repeatability_sigma,
              1.0,
              pkm::test::sigmaRatioTolerance(dev.size()));
  // The same seed repeats the same noise.
  m.reset(pkm::test::kSeed);
  const pkm::geometry::RigidTransform a = m.moveTo(command(0, 0, 200, 0, 0, 0));
  m.reset(pkm::test::kSeed);
  EXPECT_TRUE(a.matrix() == m.moveTo(command(0, 0, 200, 0, 0, 0)).matrix());
}

TEST(HexapodVirtualMachine, EncoderResolutionQuantisesTheCommand) {
  sim::StrutActuation act;
  act.encoder_resolution = 0.001;
  sim::HexapodVirtualMachine m(pkm::test::millingModel(), {}, act);
  (void)m.moveTo(command(1.23456, 0, 200, 0, 0, 0));
  for (int i = 0; i < kin::kStruts; ++i) {
    const double counts = m.commandedReadings()[i] / act.encoder_resolution;
    EXPECT_NEAR(counts, std::round(counts), 1e-6);
  }
  act.encoder_resolution = -1;
  EXPECT_THROW(sim::HexapodVirtualMachine(pkm::test::millingModel(), {}, act),
               pkm::InvalidArgument);
}

TEST(HexapodVirtualMachine, RefusesInchAndBadCommands) {
  EXPECT_THROW(sim::HexapodVirtualMachine(pkm::test::linuxcncSimModel(), {}), pkm::InvalidArgument);
  sim::HexapodVirtualMachine m(pkm::test::millingModel(), {});
  EXPECT_THROW((void)m.moveTo(command(0, 0, NAN, 0, 0, 0)), pkm::InvalidArgument);
  EXPECT_THROW((void)m.moveTo(Eigen::VectorXd::Zero(3)), pkm::InvalidArgument);
}

TEST(HexapodVirtualMachine, TheTrueModelInTheControllerRemovesTheAssemblyErrors) {
  sim::HexapodAssemblyErrors e;
  e.length_offset << 0.4, -0.3, 0.2, -0.5, 0.1, 0.3;
  e.base_joint[2] = Eigen::Vector3d(1.0, -2.0, 0.5);
  sim::HexapodVirtualMachine m(pkm::test::millingModel(), e);
  const Eigen::VectorXd c = command(12, -7, 205, 0.04, -0.03, 0.06);
  EXPECT_GT((m.moveTo(c).translation() - m.nominalPose(c).translation()).norm(), 0.1);
  m.setControllerModel(m.truth());  // a perfect calibration loaded into the controller
  EXPECT_EQ(m.controller().name, m.truth().name);
  const pkm::geometry::RigidTransform actual = m.moveTo(c);
  EXPECT_NEAR((actual.matrix() - m.nominalPose(c).matrix()).norm(), 0.0, kTolRoundTrip);
  kin::HexapodModel inch = m.truth();
  inch.unit = pkm::LengthUnit::kInch;
  EXPECT_THROW(m.setControllerModel(inch), pkm::InvalidArgument);
}

}  // namespace
