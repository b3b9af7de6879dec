// calibration::registerMeasurementFrame and expressInWorld: exact references give the placement
// and zero residuals; the covariance is σ²(AᵀA)⁻¹ checked against the scatter of noisy fits; too
// few or collinear references are refused; data moved into world lose their measurement frame.
#include "pkm/calibration/frame_registration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/pose_rpy.hpp"

namespace pkm::calibration {
namespace PKM_TEST_NS {

constexpr double kExact = 1e-9;            // mm, exact data
constexpr double kSigma = 0.005;           // mm, reference noise of the Monte Carlo check
constexpr int kTrials = 2000;              // noisy fits
constexpr double kScatterTolerance = 0.1;  // relative, of a σ from 2000 trials (≈ 1.6 % σ of σ)

const std::vector<Eigen::Vector3d> kNests = {
    {-500, -500, 0}, {500, -500, 0}, {500, 500, 0}, {-500, 500, 0}, {0, 0, 0}, {0, -700, 0}};

geometry::RigidTransform placement() {
  return geometry::makeTransform(geometry::rotationFromRpy(Eigen::Vector3d(0.01, -0.02, 2.6)),
                                 Eigen::Vector3d(1500, -900, 350));
}

std::vector<Eigen::Vector3d> readings(const geometry::RigidTransform& world_T_tracker) {
  std::vector<Eigen::Vector3d> m;
  for (const Eigen::Vector3d& n : kNests) m.push_back(world_T_tracker.inverse() * n);
  return m;
}

TEST(FrameRegistration, ExactReferencesGiveThePlacement) {
  const FrameRegistration r = registerMeasurementFrame(kNests, readings(placement()));
  EXPECT_LT((r.world_T_measurement.matrix() - placement().matrix()).norm(), kExact);
  EXPECT_EQ(r.references, 6);
  EXPECT_LT(r.max, kExact);
  // The stated σ is the floor of the covariance's σ.
  const FrameRegistration stated = registerMeasurementFrame(kNests, readings(placement()), 0.01);
  EXPECT_DOUBLE_EQ(stated.sigma, 0.01);
  // At the nests' centroid (0, -33.3, 0) a translation σ of 0.01/√6 in each direction.
  EXPECT_NEAR(stated.uncertaintyAt(Eigen::Vector3d(0, -700.0 / 6.0, 0)),
              0.01 / std::sqrt(6.0),
              1e-3 * 0.01);
}

TEST(FrameRegistration, TheCovarianceIsTheScatterOfNoisyFits) {
  std::mt19937_64 rng(37);
  std::normal_distribution<double> noise(0.0, kSigma);
  const FrameRegistration exact = registerMeasurementFrame(kNests, readings(placement()), kSigma);
  Eigen::Matrix<double, 6, 1> sum2 = Eigen::Matrix<double, 6, 1>::Zero();
  for (int t = 0; t < kTrials; ++t) {
    std::vector<Eigen::Vector3d> m = readings(placement());
    for (Eigen::Vector3d& p : m) p += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    const geometry::RigidTransform T = registerMeasurementFrame(kNests, m).world_T_measurement;
    // The left perturbation (δt, δω) of T against the true placement.
    const Eigen::Matrix3d dR = T.linear() * placement().linear().transpose();
    const Eigen::Vector3d dw = geometry::so3Log(dR);
    const Eigen::Vector3d dt = T.translation() - dR * placement().translation();
    Eigen::Matrix<double, 6, 1> d;
    d << dt, dw;
    sum2 += d.cwiseProduct(d);
  }
  for (Eigen::Index k = 0; k < 6; ++k) {
    const double scatter = std::sqrt(sum2[k] / kTrials);
    EXPECT_NEAR(scatter / std::sqrt(exact.covariance(k, k)), 1.0, kScatterTolerance) << k;
  }
}

TEST(FrameRegistration, TooFewOrCollinearReferencesAreRefused) {
  const std::vector<Eigen::Vector3d> line = {{0, 0, 0}, {100, 0, 0}, {200, 0, 0}};
  EXPECT_THROW((void)registerMeasurementFrame(line, line), InvalidArgument);
  const std::vector<Eigen::Vector3d> two = {{0, 0, 0}, {100, 0, 0}};
  EXPECT_THROW((void)registerMeasurementFrame(two, two), InvalidArgument);
  EXPECT_THROW((void)registerMeasurementFrame(kNests, readings(placement()), -1.0),
               InvalidArgument);
}

TEST(FrameRegistration, ExpressInWorldMovesPosesAndPointsAndDropsTheFrame) {
  HexapodCalibrationData data;
  PoseObservation pose;
  pose.pose.position = Eigen::Vector3d(10, 20, 30);
  pose.pose.rpy = Eigen::Vector3d(0.1, 0.0, -0.2);
  data.poses.push_back(pose);
  data.points.push_back({kinematics::StrutVector::Zero(), Eigen::Vector3d(1, 2, 3)});
  data.measurement_frame = geometry::RigidTransform::Identity();
  expressInWorld(data, placement());
  EXPECT_FALSE(data.measurement_frame.has_value());
  const geometry::RigidTransform want = placement() * kinematics::toRigidTransform(pose.pose);
  EXPECT_LT((kinematics::toRigidTransform(data.poses[0].pose).matrix() - want.matrix()).norm(),
            kExact);
  EXPECT_LT((data.points[0].point - placement() * Eigen::Vector3d(1, 2, 3)).norm(), kExact);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration
