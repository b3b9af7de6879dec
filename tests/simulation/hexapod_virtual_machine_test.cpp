// HexapodVirtualMachine: nominal behaviour without errors, a strut length offset with its
// first-order pose error J⁻¹·δ, backlash (hysteresis), repeatability spread, encoder resolution.
#include "pkm/simulation/hexapod_virtual_machine.hpp"

#include <gtest/gtest.h>

#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "pkm/simulation/compliance.hpp"
#include "support/sample_models.hpp"
#include "support/statistics.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

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

/// The realistic hexapod compliance without clearance: 150 kg on the axis, 20 kg struts.
sim::HexapodCompliance gravity() {
  sim::HexapodCompliance c;
  c.platform_mass_kg = 150.0;
  c.platform_com_mm = {0, 0, -100};
  c.strut_mass_kg = 20.0;
  c.strut_com_fraction = 0.5;
  c.strut_stiffness_n_per_um = 50.0;
  return c;
}

TEST(HexapodVirtualMachine, GravitySagOfASymmetricPoseIsWeightOver6kCos2) {
  // Pure z pose of the D3-symmetric machine: every strut carries C = W/(6·u_z), W = (m_p +
  // 6·η·m_s)·g, and stretches by |C|/k, so the platform drops by W/(6·k·u_z²); the joint clearance
  // c taken up in tension adds c/|u_z|.
  sim::HexapodVirtualMachine m(pkm::test::millingModel(), {});
  sim::HexapodCompliance c = gravity();
  m.setCompliance(c);
  const Eigen::VectorXd at = command(0, 0, 250, 0, 0, 0);
  const pkm::geometry::RigidTransform sagged = m.moveTo(at);
  kin::HexapodData data(m.truth());
  (void)kin::inverseKinematics(
      m.truth(), data, m.nominalPose(at).translation(), Eigen::Matrix3d::Identity());
  const double uz = data.unit_leg[0].z();
  const double weight =
      (c.platform_mass_kg + 6 * c.strut_com_fraction * c.strut_mass_kg) * sim::kStandardGravity;
  const double drop = weight / (6 * c.strut_stiffness_n_per_um * 1e3 * uz * uz);
  const Eigen::Vector3d d = sagged.translation() - m.nominalPose(at).translation();
  EXPECT_NEAR(d.z(), -drop, 1e-3 * drop);  // first order: the drop is µm on struts of 900 mm
  EXPECT_NEAR(d.head<2>().norm(), 0.0, 1e-9);
  EXPECT_NEAR(m.strutLoads()[0], weight / (6 * uz), 1e-9);
  c.joint_clearance_mm = 4e-3;
  m.setCompliance(c);
  const double drop_c = drop + c.joint_clearance_mm / std::abs(uz);
  EXPECT_NEAR(
      m.moveTo(at).translation().z() - m.nominalPose(at).translation().z(), -drop_c, 1e-3 * drop_c);
  m.setCompliance(std::nullopt);
  EXPECT_NEAR((m.moveTo(at).matrix() - m.nominalPose(at).matrix()).norm(), 0.0, kTolRoundTrip);
  c.strut_stiffness_n_per_um = 0.0;
  EXPECT_THROW(m.setCompliance(c), pkm::InvalidArgument);
}

TEST(HexapodVirtualMachine, GravitySagChangesWithThePose) {
  // Not a constant offset: the drop differs between poses by more than a micrometre.
  sim::HexapodVirtualMachine m(pkm::test::millingModel(), {});
  m.setCompliance(gravity());
  const auto drop = [&](const Eigen::VectorXd& c) {
    return m.moveTo(c).translation().z() - m.nominalPose(c).translation().z();
  };
  EXPECT_GT(std::abs(drop(command(0, 0, 150, 0, 0, 0)) - drop(command(150, 0, 300, 0, 0.1, 0))),
            1e-3);
}

TEST(HexapodVirtualMachine, JointClearanceJumpsWhereAStrutsLoadReverses) {
  // Put the centre of mass where strut 0 carries nothing at x = 0 (its load is linear in the
  // centre of mass), then step x across 0: strut 0's load changes sign and its joint distance
  // jumps by 2c (shorter under compression), the other struts' by nothing.
  const kin::HexapodModel model = pkm::test::millingModel();
  sim::HexapodCompliance c = gravity();
  c.strut_mass_kg = 0.0;
  const auto load0 = [&](double com_x, double x) {
    c.platform_com_mm.x() = com_x;
    kin::HexapodData d(model);
    (void)kin::inverseKinematics(model, d, Eigen::Vector3d(x, 0, 250), Eigen::Matrix3d::Identity());
    return sim::hexapodStrutLoads(model, d, c)[0];
  };
  const double a = load0(0.0, 0.0), b = load0(1000.0, 0.0) - a;
  const double com_x = -a / b * 1000.0;
  c.platform_com_mm.x() = com_x;
  c.joint_clearance_mm = 4e-3;
  sim::HexapodVirtualMachine m(model, {});
  m.setCompliance(c);
  const double step = 1e-5;
  const kin::StrutVector before = trueReadings(m, m.moveTo(command(-step, 0, 250, 0, 0, 0)));
  const double load_before = m.strutLoads()[0];
  const kin::StrutVector after = trueReadings(m, m.moveTo(command(step, 0, 250, 0, 0, 0)));
  const double load_after = m.strutLoads()[0];
  ASSERT_LT(load_before * load_after, 0.0);
  const double jump = load_after > 0.0 ? -2 * c.joint_clearance_mm : 2 * c.joint_clearance_mm;
  const double travel = 2 * step;  // the command's own change of a strut, at most the step
  EXPECT_NEAR(after[0] - before[0], jump, travel);
  for (Eigen::Index i = 1; i < kin::kStruts; ++i)
    EXPECT_LT(std::abs(after[i] - before[i]), travel) << i;
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

}  // namespace PKM_TEST_NS
