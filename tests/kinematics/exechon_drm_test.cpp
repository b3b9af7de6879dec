#include "pkm/kinematics/exechon_drm.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <iostream>
#include <numbers>

#include "kinematics/exechon_sample_models.hpp"
#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace pkm::kinematics {
namespace PKM_TEST_NS {

/// The seed paper's fit quality: the 5th-order model is within 0.1° of the computed DRM.
constexpr double kPaperFitDeviation = 0.1;  // deg

Eigen::Matrix3d rot(const Eigen::Vector3d& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

TEST(ExechonDrm, TwistAboutToolAxis) {
  const Eigen::Matrix3d ref = rot({1, 2, 3}, 0.7);
  EXPECT_EQ(dependentRotation(ref, ref), 0.0);
  EXPECT_NEAR(dependentRotation(ref * rot({0, 0, 1}, 0.3), ref), 0.3, test::kTolExact);
  EXPECT_NEAR(dependentRotation(ref * rot({0, 0, 1}, -2.9), ref), -2.9, test::kTolExact);
  EXPECT_NEAR(
      dependentRotation(ref * rot({1, -1, 0}, 0.4), ref), 0.0, test::kTolExact);  // pure swing
  // swing · twist: the twist is recovered.
  EXPECT_NEAR(dependentRotation(ref * rot({1, 0.5, 0}, 0.4) * rot({0, 0, 1}, 0.25), ref),
              0.25,
              test::kTolExact);
}

TEST(ExechonDrm, ZeroAtReferenceAndNonZeroElsewhere) {
  const ExechonModel m = test::machineModel();
  ExechonData data(m);
  const ExechonToolPose reference{{0, 0, 0}, {0, 0, -1}};
  double phi = 1.0;
  ASSERT_EQ(dependentRotation(m, data, reference, reference, &phi), ExechonIkStatus::kOk);
  EXPECT_EQ(phi, 0.0);
  ASSERT_EQ(dependentRotation(m, data, {{50, -30, 20}, {0, 0, -1}}, reference, &phi),
            ExechonIkStatus::kOk);
  EXPECT_GT(std::abs(phi), 1e-4);  // the parasitic platform rotation turns the tool about its axis
  EXPECT_LT((data.world_u_tool - Eigen::Vector3d(0, 0, -1)).norm(), test::kTolRoundTrip);
  const Eigen::Vector3d on_axis =
      m.world_T_zoppi * Eigen::Vector3d(0, 100, 0);  // wrist point on jb
  const ExechonToolPose bad{on_axis + m.wrist.tool_length * reference.direction,
                            reference.direction};
  phi = 1.0;
  EXPECT_EQ(dependentRotation(m, data, bad, reference, &phi), ExechonIkStatus::kUnreachable);
  EXPECT_EQ(dependentRotation(m, data, reference, bad, &phi), ExechonIkStatus::kUnreachable);
  EXPECT_EQ(phi, 1.0);
}

/// Samples a 1° circle at the seed paper's ring position (mm) and checks closure and smoothness.
DrmCircleResult smoothCircle(const ExechonModel& m,
                             const Eigen::Vector3d& direction,
                             double radius) {
  ExechonData data(m);
  DrmCircleOptions options;
  options.centre = {-0.625, 200.914, -168};
  options.direction = direction;
  options.radius = radius;
  const DrmCircleResult r = sampleDrmCircle(m, data, options);
  EXPECT_TRUE(r.ok()) << toString(r.status) << " at " << r.failed_index;
  if (!r.ok()) return r;
  EXPECT_EQ(r.theta.size(), 361u);
  EXPECT_NEAR(r.theta.back(), 2 * std::numbers::pi, test::kTolExact);
  EXPECT_NEAR(
      r.phi.front(), r.phi.back(), test::kTolRoundTrip);  // closed circle, same configuration
  double worst_step = 0.0, worst_curve = 0.0;  // second differences small against first differences
  for (std::size_t i = 1; i + 1 < r.phi.size(); ++i) {
    worst_step = std::max(worst_step, std::abs(r.phi[i] - r.phi[i - 1]));
    worst_curve = std::max(worst_curve, std::abs(r.phi[i + 1] - 2 * r.phi[i] + r.phi[i - 1]));
  }
  EXPECT_LT(worst_curve, 0.1 * worst_step + test::kTolRoundTrip);
  EXPECT_GT(r.max_abs_phi, 0.0);
  std::cout << "DRM circle r = " << radius << " mm, tool tilt "
            << radToDeg(std::acos(-direction.normalized().z()))
            << " deg: max |phi| = " << radToDeg(r.max_abs_phi)
            << " deg, 5th-order fit max deviation = " << radToDeg(r.max_fit_deviation) << " deg\n";
  return r;
}

/// Tool tilted 30° from the wrist's zero direction, so that A stays away from the pole.
const Eigen::Vector3d kTilted(std::sin(degToRad(30)), 0, -std::cos(degToRad(30)));

TEST(ExechonDrm, RingGaugeCircleFitsAFifthOrderPolynomial) {
  const DrmCircleResult r = smoothCircle(test::machineModel(), kTilted, 25);
  EXPECT_LT(radToDeg(r.max_fit_deviation), kPaperFitDeviation);
}

TEST(ExechonDrm, LargerCirclesAndThePoleAreSmoothButFitWorse) {
  const ExechonModel m = test::machineModel();
  const DrmCircleResult large = smoothCircle(m, kTilted, 100);
  // Near the wrist pole (tool along the C axis) the tool frame turns with C: a large, still smooth
  // DRM.
  const DrmCircleResult pole = smoothCircle(m, -Eigen::Vector3d::UnitZ(), 25);
  EXPECT_GT(pole.max_abs_phi, large.max_abs_phi / 4);
}

TEST(ExechonDrm, FitReproducesAPolynomial) {
  const std::array<double, 6> c{0.1, -0.2, 0.03, 0.004, -0.0005, 0.00006};
  std::vector<double> theta, phi;
  for (int k = 0; k <= 36; ++k) {
    theta.push_back(2 * std::numbers::pi * k / 36);
    phi.push_back(evaluateDrmPolynomial(c, theta.back()));
  }
  const std::array<double, 6> fit = fitDrmPolynomial(theta, phi);
  for (std::size_t j = 0; j < 6; ++j) EXPECT_NEAR(fit[j], c[j], test::kTolRoundTrip);
  EXPECT_THROW(static_cast<void>(fitDrmPolynomial({1, 2, 3}, {1, 2, 3})), InvalidArgument);
}

TEST(ExechonDrm, BadOptionsThrowAndUnreachableCirclesReportStatus) {
  const ExechonModel m = test::machineModel();
  ExechonData data(m);
  DrmCircleOptions options;
  EXPECT_THROW(static_cast<void>(sampleDrmCircle(m, data, options)), InvalidArgument);  // radius 0
  options.radius = 10;
  options.step = 0;
  EXPECT_THROW(static_cast<void>(sampleDrmCircle(m, data, options)), InvalidArgument);
  options.step = degToRad(5);
  options.direction.setZero();
  EXPECT_THROW(static_cast<void>(sampleDrmCircle(m, data, options)), InvalidArgument);
  // A circle whose wrist points cross Zoppi's base axis is unreachable there.
  options.direction = -Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d on_axis = m.world_T_zoppi * Eigen::Vector3d(0, 100, 0);
  options.centre = on_axis + m.wrist.tool_length * options.direction;
  options.radius = 0.5 * m.tripod.hx;
  const DrmCircleResult r = sampleDrmCircle(m, data, options);
  EXPECT_EQ(r.status, ExechonIkStatus::kUnreachable);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::kinematics
