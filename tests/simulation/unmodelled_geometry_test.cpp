// The unmodelled geometry of the true machines (unmodelled_geometry.hpp): each effect against its
// closed form (a screw's lead error at the reading where its sine peaks, a U-joint's shifted
// point for a given strut direction), the hexapod's loop closure with both, the draws from the
// environment's magnitudes, and determinism per seed.
#include "pkm/simulation/unmodelled_geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "pkm/core/error.hpp"
#include "pkm/kinematics/pose_rpy.hpp"
#include "pkm/simulation/campaign.hpp"
#include "pkm/simulation/environment.hpp"
#include "pkm/simulation/hexapod_virtual_machine.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace pkm::simulation {
namespace PKM_TEST_NS {

using kinematics::HexapodModel;

constexpr double kPi = std::numbers::pi;
constexpr double kLengthTol = 1e-12;  ///< mm, closed forms evaluated in double
constexpr double kClosureTol = 1e-8;  ///< mm, FK solved to 1e-9 and the shifts to 1e-12
constexpr double kAmplitude = 0.004;  ///< mm, a periodic lead error (V_2π = 8 µm)
constexpr double kJointOffset = 0.5;  ///< mm, a U-joint axis offset (large, to see it clearly)
constexpr int kFixedPointSteps = 20;  ///< the test's own iteration of the joint shifts

/// A command a little away from home, tilted, so every strut swings.
Eigen::VectorXd command() {
  Eigen::VectorXd c(6);
  c << 30.0, -20.0, 10.0, 0.05, -0.04, 0.1;
  c.head<3>() += test::millingModel().home.position;
  return c;
}

/// The distance of strut i's joint centres (point joints) at the pose world_T_tool.
double pointDistance(const HexapodModel& m, int i, const geometry::RigidTransform& T) {
  return (T * m.effectivePlatform(i) - m.effectiveBase(i)).norm();
}

TEST(ScrewLeadError, EachTermHasItsClosedForm) {
  ScrewLeadError e;
  e.periodic_amplitude = kAmplitude;
  e.lead = 10.0;
  EXPECT_NEAR(e.at(2.5), kAmplitude, kLengthTol);   // sin(π/2)
  EXPECT_NEAR(e.at(7.5), -kAmplitude, kLengthTol);  // sin(3π/2)
  EXPECT_NEAR(e.at(105.0), 0.0, kLengthTol);
  ScrewLeadError p;
  p.progressive = 100e-6;  // 100 µm/m
  p.reference = 250.0;
  EXPECT_NEAR(p.at(550.0), 0.030, kLengthTol);  // 300 mm from the reference
  EXPECT_NEAR(p.at(250.0), 0.0, kLengthTol);
  ScrewLeadError w;
  w.wave_amplitude = 0.010;
  w.wave_length = 300.0;
  w.wave_phase = kPi / 2;
  EXPECT_NEAR(w.at(0.0), 0.010, kLengthTol);
  EXPECT_NEAR(w.at(150.0), -0.010, kLengthTol);
  EXPECT_TRUE(ScrewLeadError{}.isZero());
  EXPECT_EQ(ScrewLeadError{}.at(123.0), 0.0);
  ScrewLeadError bad;
  bad.lead = 0.0;
  EXPECT_THROW(bad.validate(), InvalidArgument);
}

TEST(UJointOffset, ShiftIsTheOffsetAlongThePartOfTheStrutAcrossTheFirstAxis) {
  UJointOffset j;
  j.first_axis = Eigen::Vector3d::UnitX();
  j.offset = kJointOffset;
  // A strut perpendicular to the first axis: the shift lies along it (a pure length offset).
  const Eigen::Vector3d u(0.0, std::sin(0.3), std::cos(0.3));
  EXPECT_LT((j.shift(u) - kJointOffset * u).norm(), kLengthTol);
  // A strut swung by φ towards the first axis: the shift stays across the axis, d·(0, 0, 1).
  const double phi = 0.25;
  const Eigen::Vector3d v(std::sin(phi), 0.0, std::cos(phi));
  EXPECT_LT((j.shift(v) - kJointOffset * Eigen::Vector3d::UnitZ()).norm(), kLengthTol);
  // Its component along the strut is d·cos φ: the unabsorbed length change is d·(1 − cos φ).
  EXPECT_NEAR(j.shift(v).dot(v), kJointOffset * std::cos(phi), kLengthTol);
  EXPECT_THROW((void)j.shift(Eigen::Vector3d::UnitX()), InvalidArgument);
}

TEST(HexapodUnmodelledGeometry, APeriodicLeadErrorLengthensItsStrutByExactlyItsValue) {
  const HexapodModel nominal = test::millingModel();
  HexapodVirtualMachine vm(nominal, HexapodAssemblyErrors{});
  vm.moveTo(command());
  const double r = vm.commandedReadings()[0];
  // Phase chosen so the sine peaks at this reading: strut 0 travels r + a.
  HexapodUnmodelledGeometry g;
  g.lead[0].periodic_amplitude = kAmplitude;
  g.lead[0].lead = 5.0;
  g.lead[0].periodic_phase = kPi / 2 - 2 * kPi * r / 5.0;
  vm.setUnmodelledGeometry(g);
  vm.reset(0);
  const geometry::RigidTransform T = vm.moveTo(command());
  for (int i = 0; i < kinematics::kStruts; ++i) {
    const double expected =
        vm.commandedReadings()[i] + nominal.struts[i].length_offset + (i == 0 ? kAmplitude : 0.0);
    EXPECT_NEAR(pointDistance(nominal, i, T), expected, kClosureTol) << "strut " << i;
  }
}

TEST(HexapodUnmodelledGeometry, UJointOffsetsCloseTheLoopsThroughTheShiftedPoints) {
  const HexapodModel nominal = test::millingModel();
  HexapodVirtualMachine vm(nominal, HexapodAssemblyErrors{});
  HexapodUnmodelledGeometry g;
  g.platform_joint[2].first_axis = Eigen::Vector3d(1.0, 1.0, 0.0).normalized();
  g.platform_joint[2].offset = kJointOffset;
  g.base_joint[4].first_axis = Eigen::Vector3d::UnitY();
  g.base_joint[4].offset = -kJointOffset;
  vm.setUnmodelledGeometry(g);
  const geometry::RigidTransform T = vm.moveTo(command());
  const Eigen::Matrix3d R = T.linear();
  for (int i = 0; i < kinematics::kStruts; ++i) {
    const auto k = static_cast<std::size_t>(i);
    // The test's own fixed point: u = direction between the points shifted along u.
    Eigen::Vector3d b = nominal.effectiveBase(i), p = T * nominal.effectivePlatform(i);
    for (int n = 0; n < kFixedPointSteps; ++n) {
      const Eigen::Vector3d u = (p - b).normalized();
      b = nominal.effectiveBase(i) + g.base_joint[k].shift(u);
      p = T * (nominal.effectivePlatform(i) + g.platform_joint[k].shift(R.transpose() * u));
    }
    EXPECT_NEAR(
        (p - b).norm(), vm.commandedReadings()[i] + nominal.struts[k].length_offset, kClosureTol)
        << "strut " << i;
  }
  // The offsets moved the platform: a machine without them sits elsewhere.
  HexapodVirtualMachine plain(nominal, HexapodAssemblyErrors{});
  EXPECT_GT((plain.moveTo(command()).translation() - T.translation()).norm(), 0.01);
}

TEST(HexapodUnmodelledGeometry, DrawsFollowTheEnvironmentAndRepeatPerSeed) {
  const HexapodModel nominal = test::millingModel();
  const GeometryEnvironment env = realisticGeometry();
  RandomStream a(test::kSeed, "geometry"), b(test::kSeed, "geometry"), c(test::kSeed + 1, "g");
  const HexapodUnmodelledGeometry ga = drawHexapodGeometry(env, nominal, a);
  const HexapodUnmodelledGeometry gb = drawHexapodGeometry(env, nominal, b);
  const HexapodUnmodelledGeometry gc = drawHexapodGeometry(env, nominal, c);
  for (std::size_t i = 0; i < kinematics::kStruts; ++i) {
    EXPECT_EQ(ga.lead[i].progressive, gb.lead[i].progressive);
    EXPECT_EQ(ga.platform_joint[i].offset, gb.platform_joint[i].offset);
    EXPECT_NE(ga.lead[i].progressive, gc.lead[i].progressive);
    EXPECT_LE(std::abs(ga.lead[i].progressive), env.lead_progressive);
    EXPECT_EQ(ga.lead[i].wave_amplitude, env.lead_wave_mm);
    EXPECT_EQ(ga.lead[i].periodic_amplitude, env.lead_periodic_mm);
    EXPECT_LE(std::abs(ga.platform_joint[i].offset), env.joint_axis_offset_mm);
    EXPECT_EQ(ga.base_joint[i].offset, 0.0);  // ball-and-socket base joints (seed 004)
    EXPECT_NEAR(ga.platform_joint[i].first_axis.z(), 0.0, kLengthTol);  // horizontal
  }
  // Off: nothing; invalid: refused.
  EXPECT_TRUE(drawHexapodGeometry(GeometryEnvironment{}, nominal, a).isZero());
  GeometryEnvironment bad = env;
  bad.screw_lead_mm = -1.0;
  EXPECT_THROW((void)drawHexapodGeometry(bad, nominal, a), InvalidArgument);
}

TEST(HexapodUnmodelledGeometry, TheCampaignPutsItIntoTheMachineAndTakesItOutAgain) {
  EXPECT_FALSE(environmentPreset("ideal")->geometry.enabled);
  EXPECT_TRUE(environmentPreset("realistic")->geometry.enabled);
  Campaign campaign;
  campaign.name = "geometry";
  auto vm = std::make_shared<HexapodVirtualMachine>(test::millingModel(), HexapodAssemblyErrors{});
  campaign.machine = vm;
  campaign.environment = *environmentPreset("realistic");
  applyGeometryEnvironment(campaign, test::kSeed);
  EXPECT_FALSE(vm->unmodelledGeometry().isZero());
  const double first = vm->unmodelledGeometry().lead[3].wave_phase;
  applyGeometryEnvironment(campaign, test::kSeed);
  EXPECT_EQ(vm->unmodelledGeometry().lead[3].wave_phase, first);  // deterministic per seed
  campaign.environment = *environmentPreset("ideal");
  applyGeometryEnvironment(campaign, test::kSeed);
  EXPECT_TRUE(vm->unmodelledGeometry().isZero());
}

TEST(ExechonLegLeadErrors, AddEachLegsErrorToItsReading) {
  ExechonLegLeadErrors lead{};
  lead[1].progressive = 1e-4;
  lead[1].reference = 100.0;
  kinematics::ExechonJoints j;
  j.readings << 300.0, 400.0, 500.0;
  j.c = 0.1;
  const kinematics::ExechonJoints t = withLeadErrors(j, lead);
  EXPECT_EQ(t.readings[0], 300.0);
  EXPECT_NEAR(t.readings[1], 400.0 + 0.03, kLengthTol);
  EXPECT_EQ(t.readings[2], 500.0);
  EXPECT_EQ(t.c, 0.1);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::simulation
