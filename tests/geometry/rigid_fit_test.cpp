#include "pkm/geometry/rigid_fit.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <random>

#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/geometry/so3.hpp"
#include "support/tolerances.hpp"

namespace pkm::geometry {
namespace PKM_TEST_NS {

TEST(RigidFit, RecoversAKnownTransformExactly) {
  std::mt19937 rng(test::kSeed);
  std::uniform_real_distribution<double> u(-500.0, 500.0);
  // A 150°-class rotation.
  const RigidTransform truth =
      makeTransform(so3Exp(Eigen::Vector3d(0.2, -0.4, 2.6)), Eigen::Vector3d(1500, -900, 350));
  std::vector<Eigen::Vector3d> a, b;
  for (int k = 0; k < 10; ++k) {
    b.emplace_back(u(rng), u(rng), u(rng));
    a.push_back(truth * b.back());
  }
  const RigidTransform fit = fitRigidTransform(a, b);
  EXPECT_LT((fit.linear() - truth.linear()).cwiseAbs().maxCoeff(), test::kTolExact * 100);
  EXPECT_LT((fit.translation() - truth.translation()).cwiseAbs().maxCoeff(), test::kTolRoundTrip);
  EXPECT_NEAR(fit.linear().determinant(), 1.0, test::kTolExact);
}

TEST(RigidFit, PlanarPointsGiveAProperRotation) {
  // Coplanar points: the reflection guard must keep det = +1.
  std::vector<Eigen::Vector3d> b{{0, 0, 0}, {100, 0, 0}, {0, 100, 0}, {100, 100, 0}};
  const Eigen::Matrix3d R = so3Exp(Eigen::Vector3d(0.0, 0.0, 0.5));
  std::vector<Eigen::Vector3d> a;
  for (const auto& p : b) a.push_back(R * p);
  const RigidTransform fit = fitRigidTransform(a, b);
  EXPECT_LT((fit.linear() - R).cwiseAbs().maxCoeff(), test::kTolRoundTrip);
  EXPECT_NEAR(fit.linear().determinant(), 1.0, test::kTolExact);
}

TEST(RigidFit, RejectsDegenerateInput) {
  const std::vector<Eigen::Vector3d> line{{0, 0, 0}, {1, 1, 1}, {2, 2, 2}};
  EXPECT_THROW((void)fitRigidTransform(line, line), InvalidArgument);
  EXPECT_THROW((void)fitRigidTransform({{0, 0, 0}}, {{0, 0, 0}}), InvalidArgument);
  EXPECT_THROW((void)fitRigidTransform(line, {{0, 0, 0}}), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::geometry
