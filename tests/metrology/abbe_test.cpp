#include "pkm/metrology/abbe.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"
#include "support/tolerances.hpp"

namespace pkm::metrology {
namespace PKM_TEST_NS {

/// Second-order remainder of a 1e-4 rad rotation over a 100 mm arm: |ε|²·r/2 = 5e-7 mm.
constexpr double kTolFirstOrder = 1e-6;

geometry::ErrorTable1d angleTable(std::vector<double> x, const std::vector<double>& v) {
  Eigen::MatrixXd values(static_cast<Eigen::Index>(v.size()), 1);
  for (std::size_t k = 0; k < v.size(); ++k) values(static_cast<Eigen::Index>(k), 0) = v[k];
  return geometry::ErrorTable1d(std::move(x), values);
}

TEST(Abbe, PitchTimesVerticalOffset) {
  // Pitch ε about +y of an X axis, reflector 80 mm above the tool point: the reflector moves by
  // ε × (0, 0, 80) = (80 ε, 0, 0) along the beam x.
  const Eigen::Vector3d offset(0, 0, 80), x = Eigen::Vector3d::UnitX();
  EXPECT_NEAR(abbeError(Eigen::Vector3d(0, 2e-5, 0), offset, x), 80 * 2e-5, test::kTolExact);
  EXPECT_NEAR(abbeError(Eigen::Vector3d(0, 0, 3e-5), Eigen::Vector3d(0, 50, 0), x),
              -50 * 3e-5,
              test::kTolExact);  // yaw with a lateral offset: ε_z ẑ × 50 ŷ = -50 ε_z x̂
}

TEST(Abbe, RemovalMatchesExactRigidRotation) {
  // True tool motion along x: x_k + e(x_k). The reflector at offset r sees the rotated offset
  // R(ε)·r; removing the first-order Abbe term recovers the tool reading to second order.
  const std::vector<double> xs{0, 100, 200, 300, 400};
  const std::vector<double> pitch{0, 2e-5, 5e-5, 8e-5, 1e-4}, yaw{0, -1e-5, 0, 3e-5, 2e-5};
  const std::vector<AngularProfile> angles{{angleTable(xs, pitch), Eigen::Vector3d::UnitY()},
                                           {angleTable(xs, yaw), Eigen::Vector3d::UnitZ()}};
  const Eigen::Vector3d r(0, 40, 90), m = Eigen::Vector3d::UnitX();
  std::vector<double> readings, truth;
  for (std::size_t k = 0; k < xs.size(); ++k) {
    const double tool = xs[k] + 1e-3 * std::sin(0.01 * xs[k]);
    const Eigen::Matrix3d R = geometry::so3Exp(Eigen::Vector3d(0, pitch[k], yaw[k]));
    truth.push_back(tool);
    readings.push_back(tool + m.dot(R * r - r));  // zeroed at x = 0 where R = I
  }
  const std::vector<double> corrected = removeAbbeError(xs, readings, angles, r, m, 0.0);
  for (std::size_t k = 0; k < xs.size(); ++k) EXPECT_NEAR(corrected[k], truth[k], kTolFirstOrder);
  EXPECT_GT(std::abs(readings[3] - truth[3]), 100 * kTolFirstOrder);  // the correction matters
}

TEST(Abbe, RejectsBadInput) {
  const std::vector<double> x{0, 1}, y{0};
  EXPECT_THROW(
      (void)removeAbbeError(x, y, {}, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitX(), 0),
      InvalidArgument);
  EXPECT_THROW(
      (void)abbeError(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()),
      InvalidArgument);
  const std::vector<AngularProfile> zero_axis{
      {angleTable({0, 1}, {0, 1e-5}), Eigen::Vector3d::Zero()}};
  EXPECT_THROW(
      (void)removeAbbeError(x, x, zero_axis, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(), 0),
      InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::metrology
