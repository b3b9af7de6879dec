// Pose pre-distortion X_cmd = FK_nominal(IK_calibrated(X)): the nominal controller then commands
// exactly the strut readings the calibrated machine needs, over random poses; identity for equal
// models; path seeding; failures as results; preconditions.
#include "pkm/compensation/predistortion.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace comp = pkm::compensation;
namespace kin = pkm::kinematics;
using pkm::test::kTolRoundTrip;

constexpr double kJointError = 0.5;   // mm, joint-centre errors of the "calibrated" model
constexpr double kOffsetError = 0.2;  // mm, length-offset errors
constexpr double kReach = 60.0;       // mm, random pose range about home
constexpr double kTiltDeg = 6.0;      // degrees
constexpr int kPoses = 200;
constexpr double kMinCorrection = 0.05;  // mm: the errors must move the command noticeably

kin::HexapodModel calibratedModel(const kin::HexapodModel& nominal, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  kin::HexapodModel m = nominal;
  for (auto& s : m.struts) {
    for (int k = 0; k < 3; ++k) {
      s.world_p_base[k] += kJointError * u(rng);
      s.platform_p_joint[k] += kJointError * u(rng);
    }
    s.length_offset += kOffsetError * u(rng);
  }
  return m;
}

std::vector<kin::PoseRpy> randomPoses(const kin::HexapodModel& m, std::mt19937& rng) {
  std::vector<kin::PoseRpy> poses;
  for (int i = 0; i < kPoses; ++i) {
    poses.push_back(pkm::test::randomPose(rng, m.home, kReach, pkm::degToRad(kTiltDeg)));
  }
  return poses;
}

double maxDiff(const kin::StrutVector& a, const kin::StrutVector& b) {
  return (a - b).cwiseAbs().maxCoeff();
}

TEST(Predistortion, NominalIkOfCommandEqualsCalibratedIk) {
  std::mt19937 rng(pkm::test::kSeed);
  const kin::HexapodModel nominal = pkm::test::millingModel();
  const kin::HexapodModel calibrated = calibratedModel(nominal, rng);
  kin::HexapodData nd(nominal), cd(calibrated);
  double worst = 0.0, largest_correction = 0.0;
  for (const kin::PoseRpy& x : randomPoses(nominal, rng)) {
    const comp::PredistortionResult r = comp::predistort(nominal, calibrated, x);
    ASSERT_TRUE(r.ok()) << kin::toString(r.fk.status);
    const kin::StrutVector q_cal = kin::inverseKinematics(calibrated, cd, x);
    const kin::StrutVector q_cmd = kin::inverseKinematics(nominal, nd, r.command);
    EXPECT_EQ(r.readings, q_cal);
    worst = std::max(worst, maxDiff(q_cmd, q_cal));
    largest_correction =
        std::max(largest_correction, (r.command.position - x.position).cwiseAbs().maxCoeff());
  }
  EXPECT_LE(worst, kTolRoundTrip);
  EXPECT_GE(largest_correction, kMinCorrection);  // the test is not trivially passing
}

TEST(Predistortion, EqualModelsGiveTheDesiredPose) {
  std::mt19937 rng(pkm::test::kSeed);
  const kin::HexapodModel m = pkm::test::millingModel();
  for (const kin::PoseRpy& x : randomPoses(m, rng)) {
    const comp::PredistortionResult r = comp::predistort(m, m, x);
    ASSERT_TRUE(r.ok());
    EXPECT_LE((r.command.position - x.position).cwiseAbs().maxCoeff(), kTolRoundTrip);
    EXPECT_LE((r.command.rpy - x.rpy).cwiseAbs().maxCoeff(), kTolRoundTrip);
  }
}

TEST(Predistortion, PathMatchesSinglePoses) {
  std::mt19937 rng(pkm::test::kSeed + 1);
  const kin::HexapodModel nominal = pkm::test::millingModel();
  const kin::HexapodModel calibrated = calibratedModel(nominal, rng);
  std::vector<kin::PoseRpy> path;
  for (int i = 0; i < kPoses; ++i) {  // a circle of radius 50 mm with a tilt wave
    const double t = 2.0 * std::numbers::pi * i / kPoses;
    kin::PoseRpy p = nominal.home;
    p.position += Eigen::Vector3d(50 * std::cos(t), 50 * std::sin(t), 10 * std::sin(3 * t));
    p.rpy[0] = pkm::degToRad(3.0) * std::sin(2 * t);
    path.push_back(p);
  }
  const auto results = comp::predistortPath(nominal, calibrated, path);
  ASSERT_EQ(results.size(), path.size());
  kin::HexapodData nd(nominal), cd(calibrated);
  for (std::size_t k = 0; k < path.size(); ++k) {
    ASSERT_TRUE(results[k].ok()) << k;
    EXPECT_LE(maxDiff(kin::inverseKinematics(nominal, nd, results[k].command),
                      kin::inverseKinematics(calibrated, cd, path[k])),
              kTolRoundTrip);
  }
}

TEST(Predistortion, NonConvergenceIsAResult) {
  std::mt19937 rng(pkm::test::kSeed);
  const kin::HexapodModel nominal = pkm::test::millingModel();
  const kin::HexapodModel calibrated = calibratedModel(nominal, rng);
  comp::PredistortionOptions opt;
  opt.fk.max_iterations = 1;
  opt.fk.tolerance = 1e-15;
  kin::PoseRpy far = nominal.home;
  far.position.x() += 40.0;
  const comp::PredistortionResult r = comp::predistort(nominal, calibrated, far, nominal.home, opt);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.fk.status, kin::FkStatus::kNoConvergence);
}

TEST(Predistortion, Preconditions) {
  const kin::HexapodModel nominal = pkm::test::millingModel();
  kin::HexapodModel inch = nominal;
  inch.unit = pkm::LengthUnit::kInch;
  EXPECT_THROW((void)comp::predistort(nominal, inch, nominal.home), pkm::InvalidArgument);
  kin::PoseRpy nan = nominal.home;
  nan.position.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)comp::predistort(nominal, nominal, nan), pkm::InvalidArgument);
  comp::PredistortionOptions bad;
  bad.fk.tolerance = -1.0;
  EXPECT_THROW((void)comp::predistort(nominal, nominal, nominal.home, bad), pkm::InvalidArgument);
}

}  // namespace PKM_TEST_NS
