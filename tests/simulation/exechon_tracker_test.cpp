#include "pkm/simulation/exechon_tracker.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/exechon_checks.hpp"
#include "pkm/kinematics/exechon_data.hpp"
#include "pkm/simulation/hybrid_tripod_errors.hpp"
#include "support/tolerances.hpp"

namespace pkm::simulation {
namespace PKM_TEST_NS {

constexpr double kTilt = 0.4;  // rad

kinematics::ExechonModel nominal() { return io::loadExechonMachine("mxt700s-like").model; }

ExechonTrackerSetup setup() {
  ExechonTrackerSetup s;
  s.name = "t";
  s.count = 40;
  s.box_min = Eigen::Vector3d(-300, -300, -100);
  s.box_max = Eigen::Vector3d(300, 300, 300);
  s.max_tilt = kTilt;
  s.smr_offset = Eigen::Vector3d(40, 0, 10);
  s.world_T_tracker.translation() = Eigen::Vector3d(1500, -1000, 300);
  s.world_T_tracker.linear() = Eigen::AngleAxisd(2.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  return s;
}

TEST(ExechonTracker, IdealMachineAndInstrumentReproduceTheCommand) {
  const kinematics::ExechonModel m = nominal();
  RandomStream rng(test::kSeed);
  const ExechonTrackerSetup s = setup();
  const auto readings = simulateExechonTracker(m, m, {}, s, rng);
  ASSERT_EQ(readings.size(), 40u);
  kinematics::ExechonData work(m);
  for (const ExechonTrackerReading& r : readings) {
    EXPECT_EQ(r.measured, r.truth);  // no noise: nothing drawn
    // Commands inside the box and the tilt cone, within every limit of the nominal machine.
    EXPECT_TRUE((r.command.position.array() >= s.box_min.array()).all());
    EXPECT_TRUE((r.command.position.array() <= s.box_max.array()).all());
    EXPECT_LE(std::acos(-r.command.direction.z()), kTilt + test::kTolExact);
    EXPECT_TRUE(kinematics::checkJoints(m, work, r.joints, m.home).ok());
    // With the true model equal to the nominal one the SMR is the commanded point + offset.
    ASSERT_TRUE(kinematics::toolForwardKinematics(m, work, r.joints, m.home).ok());
    const Eigen::Vector3d expected =
        s.world_T_tracker.inverse() * (r.command.position + work.world_R_tool * s.smr_offset);
    EXPECT_LT((r.truth - expected).norm(), test::kTolRoundTrip * 1e3);
    EXPECT_LT((work.world_u_tool - r.command.direction.normalized()).norm(), test::kTolRoundTrip);
  }
}

TEST(ExechonTracker, TripodErrorsMoveTheTargetAndNoiseIsDeterministic) {
  const kinematics::ExechonModel m = nominal();
  ExechonTripodErrors e;
  e.dB = 0.5;
  e.length_offset = Eigen::Vector3d(0.3, 0, -0.2);
  const kinematics::ExechonModel actual = perturbedExechon(m, e);
  ExechonTrackerSetup s = setup();
  s.noise.range_sigma = 0.005;
  RandomStream a(test::kSeed), b(test::kSeed), c(test::kSeed);
  const auto ideal = simulateExechonTracker(m, m, {}, setup(), c);
  const auto first = simulateExechonTracker(m, actual, {}, s, a);
  const auto second = simulateExechonTracker(m, actual, {}, s, b);
  ASSERT_EQ(first.size(), second.size());
  double moved = 0.0;
  for (std::size_t k = 0; k < first.size(); ++k) {
    EXPECT_EQ(first[k].measured, second[k].measured);
    EXPECT_NE(first[k].measured, first[k].truth);
    moved = std::max(moved, (first[k].truth - ideal[k].truth).norm());
  }
  EXPECT_GT(moved, 0.1);
}

TEST(ExechonTracker, InvalidSetupsThrow) {
  const kinematics::ExechonModel m = nominal();
  RandomStream rng(test::kSeed);
  ExechonTrackerSetup s = setup();
  s.count = 0;
  EXPECT_THROW((void)simulateExechonTracker(m, m, {}, s, rng), InvalidArgument);
  s = setup();
  s.box_min.x() = 400;
  EXPECT_THROW((void)simulateExechonTracker(m, m, {}, s, rng), InvalidArgument);
  s = setup();
  s.max_tilt = 2.0;
  EXPECT_THROW((void)simulateExechonTracker(m, m, {}, s, rng), InvalidArgument);
  s = setup();
  s.box_min = Eigen::Vector3d(5000, 5000, 5000);  // unreachable: gives up after the draw budget
  s.box_max = s.box_min;
  EXPECT_THROW((void)simulateExechonTracker(m, m, {}, s, rng), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::simulation
