// Laser tracker on a hexapod virtual machine: zero noise gives the true pose exactly (checked
// against the true model's forward kinematics at the recorded strut readings), the strut readings
// are the controller's, determinism per seed, the noise spread in range, both angles and
// orientation matches the specification, presets, bad set-ups.
#include "pkm/simulation/laser_tracker.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "pkm/core/error.hpp"
#include "pkm/geometry/error_motion.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "pkm/kinematics/pose_rpy.hpp"
#include "support/sample_models.hpp"
#include "support/statistics.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace kin = pkm::kinematics;
namespace sim = pkm::simulation;
namespace geo = pkm::geometry;
using pkm::test::kTolRoundTrip;

constexpr int kRandomPoses = 40;
constexpr int kNoiseSamples = 4000;  // readings of one pose for the spread tests

/// Assembly errors of a few mm, as seed 004's machine has.
sim::HexapodAssemblyErrors someErrors() {
  sim::HexapodAssemblyErrors e;
  for (int i = 0; i < kin::kStruts; ++i) {
    const double s = i % 2 ? -1.0 : 1.0;
    e.base_joint[static_cast<std::size_t>(i)] = Eigen::Vector3d(2.0 * s, -1.5, 0.5 * i);
    e.platform_joint[static_cast<std::size_t>(i)] = Eigen::Vector3d(-0.5, 0.8 * s, 0.3);
    e.length_offset[i] = 1.2 * s;
  }
  return e;
}

sim::TrackerSetup setup(sim::TrackerMode mode) {
  sim::TrackerSetup s;
  s.name = "tracker";
  s.mode = mode;
  Eigen::VectorXd home(6);
  home << 0, 0, 200, 0, 0, 0;
  s.poses = {home};
  s.random_count = kRandomPoses;
  s.random_box.lo << -150, -150, 150, -0.15, -0.15, -0.3;
  s.random_box.hi << 150, 150, 280, 0.15, 0.15, 0.3;
  s.smr_offset = {30, -20, 60};
  s.world_T_tracker = geo::makeTransform(geo::rotationFromRpy({2e-4, -1e-4, 2.6}),
                                         Eigen::Vector3d(1500, -900, 350));
  return s;
}

std::vector<sim::TrackerReading> run(const sim::TrackerSetup& s,
                                     const sim::HexapodAssemblyErrors& e,
                                     std::uint64_t seed) {
  sim::HexapodVirtualMachine m(pkm::test::millingModel(), e);
  sim::RandomStream rng(seed);
  return sim::simulateLaserTracker(m, s, rng);
}

TEST(LaserTracker, ZeroNoiseGivesTheTruePoseOfTheTrueModel) {
  const sim::TrackerSetup s = setup(sim::TrackerMode::kPose);
  sim::HexapodVirtualMachine m(pkm::test::millingModel(), someErrors());
  sim::RandomStream rng(pkm::test::kSeed);
  const auto readings = sim::simulateLaserTracker(m, s, rng);
  ASSERT_EQ(readings.size(), s.poses.size() + kRandomPoses);
  kin::HexapodData nominal(m.nominal()), truth(m.truth());
  for (const sim::TrackerReading& r : readings) {
    EXPECT_TRUE(r.measured.matrix() == r.truth.matrix());  // ideal noise: exactly the truth
    // The strut readings are the nominal IK of the command (no encoder counts here).
    kin::PoseRpy pose;
    pose.position = r.command.head<3>();
    pose.rpy = r.command.tail<3>();
    EXPECT_TRUE(kin::inverseKinematics(m.nominal(), nominal, pose) == r.lengths);
    // Independently: the true model's FK at those readings, seen from the tracker.
    ASSERT_TRUE(kin::forwardKinematics(m.truth(), truth, r.lengths, pose).ok());
    const geo::RigidTransform world_T_target =
        geo::makeTransform(truth.world_R_platform, truth.world_p_tcp) *
        geo::translationTransform(s.smr_offset);
    const geo::RigidTransform expected = s.world_T_tracker.inverse() * world_T_target;
    EXPECT_NEAR(
        (r.measured.matrix() - expected.matrix()).cwiseAbs().maxCoeff(), 0.0, kTolRoundTrip);
  }
}

TEST(LaserTracker, WithoutErrorsTheTrackerSeesTheCommandedPose) {
  const sim::TrackerSetup s = setup(sim::TrackerMode::kPose);
  for (const sim::TrackerReading& r : run(s, {}, pkm::test::kSeed)) {
    const geo::RigidTransform world_T_target =
        s.world_T_tracker * r.measured * geo::translationTransform(-s.smr_offset);
    const geo::RigidTransform commanded =
        kin::toRigidTransform({r.command.head<3>(), r.command.tail<3>()});
    EXPECT_NEAR(
        (world_T_target.matrix() - commanded.matrix()).cwiseAbs().maxCoeff(), 0.0, kTolRoundTrip);
  }
}

TEST(LaserTracker, PointModeMeasuresOnlyThePosition) {
  sim::TrackerSetup s = setup(sim::TrackerMode::kPoint);
  s.noise = *sim::trackerNoise("laser-tracker");
  for (const sim::TrackerReading& r : run(s, someErrors(), pkm::test::kSeed)) {
    EXPECT_TRUE(r.measured.linear() == Eigen::Matrix3d::Identity());
    EXPECT_GT((r.measured.translation() - r.truth.translation()).norm(), 0.0);
  }
}

TEST(LaserTracker, SameSeedSameReadingsOtherSeedOtherReadings) {
  sim::TrackerSetup s = setup(sim::TrackerMode::kPose);
  s.noise = *sim::trackerNoise("laser-tracker");
  const auto a = run(s, someErrors(), 7), b = run(s, someErrors(), 7), c = run(s, someErrors(), 8);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_TRUE(a[i].command == b[i].command);
    EXPECT_TRUE(a[i].measured.matrix() == b[i].measured.matrix());
    EXPECT_TRUE(a[i].lengths == b[i].lengths);
  }
  EXPECT_FALSE(a[1].command == c[1].command);  // the random poses come from the stream
}

TEST(LaserTracker, NoiseSpreadMatchesTheSpecification) {
  // One pose read many times: the deviations along the line of sight, the elevation and the
  // azimuth directions and about the three tracker axes have the specified standard deviations.
  sim::TrackerSetup s = setup(sim::TrackerMode::kPose);
  s.random_count = 0;
  s.poses.assign(kNoiseSamples, s.poses.front());
  s.noise = {0.004, 2.0, 3e-6, 40e-6};
  const auto readings = run(s, someErrors(), pkm::test::kSeed);
  const Eigen::Vector3d p = readings.front().truth.translation();
  const double r = p.norm(), el = std::asin(p.z() / r), az = std::atan2(p.y(), p.x());
  const Eigen::Vector3d radial = p / r;
  const Eigen::Vector3d up(
      -std::sin(el) * std::cos(az), -std::sin(el) * std::sin(az), std::cos(el));
  const Eigen::Vector3d side(-std::sin(az), std::cos(az), 0.0);
  std::vector<double> dr, du, ds, o0, o1, o2;
  for (const sim::TrackerReading& x : readings) {
    // No machine noise: the same true pose up to the FK's round-off.
    ASSERT_LT((x.truth.matrix() - readings.front().truth.matrix()).cwiseAbs().maxCoeff(),
              kTolRoundTrip);
    const Eigen::Vector3d d = x.measured.translation() - x.truth.translation();
    dr.push_back(radial.dot(d));
    du.push_back(up.dot(d));
    ds.push_back(side.dot(d));
    const Eigen::Vector3d w = geo::so3Log(x.measured.linear() * x.truth.linear().transpose());
    o0.push_back(w[0]);
    o1.push_back(w[1]);
    o2.push_back(w[2]);
  }
  const double tol = pkm::test::sigmaRatioTolerance(readings.size());
  EXPECT_NEAR(pkm::test::sampleSigma(dr) / s.noise.rangeSigma(r), 1.0, tol);
  EXPECT_NEAR(pkm::test::sampleSigma(du) / (s.noise.angle_sigma * r), 1.0, tol);
  EXPECT_NEAR(pkm::test::sampleSigma(ds) / (s.noise.angle_sigma * r * std::cos(el)), 1.0, tol);
  for (const auto* o : {&o0, &o1, &o2}) {
    EXPECT_NEAR(pkm::test::sampleSigma(*o) / s.noise.orientation_sigma, 1.0, tol);
    EXPECT_NEAR(pkm::test::sampleMean(*o),
                0.0,
                pkm::test::meanTolerance(o->size(), s.noise.orientation_sigma));
  }
  EXPECT_NEAR(
      pkm::test::sampleMean(dr), 0.0, pkm::test::meanTolerance(dr.size(), s.noise.rangeSigma(r)));
}

TEST(LaserTracker, PresetIsTheDatasheetFigureHalved) {
  const sim::TrackerNoise n = *sim::trackerNoise("laser-tracker");
  constexpr double kMetre = 1000.0;  // mm
  // U(k = 2) = 15 µm + 6 µm/m: 7.5 µm constant, 3 µm/m in range and across the line of sight.
  EXPECT_DOUBLE_EQ(n.rangeSigma(0.0), 0.0075);
  EXPECT_DOUBLE_EQ(n.rangeSigma(kMetre), std::hypot(0.0075, 0.003));
  EXPECT_DOUBLE_EQ(n.angle_sigma * kMetre, 0.003);
  EXPECT_DOUBLE_EQ(n.orientation_sigma, 0.005 * std::numbers::pi / 180.0);
  EXPECT_TRUE(sim::trackerNoise("ideal")->ideal());
  EXPECT_FALSE(sim::trackerNoise("no-such-tracker").has_value());
  EXPECT_EQ(sim::trackerNoiseNames().size(), 2U);
  EXPECT_STREQ(sim::toString(sim::TrackerMode::kPoint), "point");
  EXPECT_STREQ(sim::toString(sim::TrackerMode::kPose), "pose");
}

TEST(LaserTracker, APerfectTrackerReadsTheTruthAndDrawsAsTheNoisyOne) {
  // The perfect-instrument twin of `pkm validate coverage` keeps its random stream aligned with
  // the measured run: the same variates are drawn, the true reading returned.
  sim::TrackerNoise noisy = *sim::trackerNoise("laser-tracker");
  sim::TrackerNoise perfect = noisy;
  perfect.perfect = true;
  const Eigen::Vector3d p(800.0, -300.0, 450.0);
  const Eigen::Matrix3d R = geo::rotationFromRpy(Eigen::Vector3d(0.1, -0.2, 0.3));
  sim::RandomStream a(pkm::test::kSeed), b(pkm::test::kSeed);
  const Eigen::Vector3d measured = noisy.point(p, a);
  EXPECT_GT((measured - p).norm(), 0.0);
  EXPECT_EQ(perfect.point(p, b), p);
  EXPECT_GT((noisy.rotation(R, a) - R).norm(), 0.0);
  EXPECT_EQ(perfect.rotation(R, b), R);
  EXPECT_EQ(a.normal(1.0), b.normal(1.0));  // both streams are at the same place
}

TEST(LaserTracker, BadSetUpsThrow) {
  sim::HexapodVirtualMachine m(pkm::test::millingModel(), {});
  sim::RandomStream rng(pkm::test::kSeed);
  sim::TrackerSetup s = setup(sim::TrackerMode::kPose);
  s.poses.clear();
  s.random_count = 0;
  EXPECT_THROW((void)sim::simulateLaserTracker(m, s, rng), pkm::InvalidArgument);
  s = setup(sim::TrackerMode::kPose);
  s.world_T_tracker.linear() *= 2.0;  // not rigid
  EXPECT_THROW((void)sim::simulateLaserTracker(m, s, rng), pkm::InvalidArgument);
  s = setup(sim::TrackerMode::kPose);
  s.noise.angle_sigma = -1.0;
  EXPECT_THROW((void)sim::simulateLaserTracker(m, s, rng), pkm::InvalidArgument);
  s = setup(sim::TrackerMode::kPose);
  s.poses.front().resize(5);
  EXPECT_THROW((void)sim::simulateLaserTracker(m, s, rng), pkm::InvalidArgument);
  s = setup(sim::TrackerMode::kPose);
  s.random_box.lo[2] = 5000.0;  // far below the base, outside the workspace
  s.random_box.hi[2] = 5100.0;
  EXPECT_THROW((void)sim::simulateLaserTracker(m, s, rng), pkm::InvalidArgument);
}

}  // namespace PKM_TEST_NS
