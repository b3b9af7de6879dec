#include "pkm/geometry/error_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace pkm::geometry {
namespace PKM_TEST_NS {

using test::kTolExact;
using Axes = std::array<std::vector<double>, 3>;

/// Uneven spacing along each axis, over a PKM-sized volume (mm).
Axes sampleAxes() {
  return {std::vector<double>{-350.0, -200.0, -20.0, 100.0, 350.0},
          std::vector<double>{-350.0, 0.0, 125.0, 350.0},
          std::vector<double>{-100.0, 30.0, 120.0, 210.0, 300.0}};
}

Eigen::Vector3d randomPoint(std::mt19937& rng, const Axes& axes, double margin = 0.0) {
  Eigen::Vector3d p;
  for (int a = 0; a < 3; ++a) {
    const auto& ax = axes[static_cast<std::size_t>(a)];
    p[a] = std::uniform_real_distribution<double>(ax.front() - margin, ax.back() + margin)(rng);
  }
  return p;
}

/// An affine field of two components: A·p + b.
struct Affine {
  Eigen::Matrix<double, 2, 3> A;
  Eigen::Vector2d b;
  Eigen::VectorXd operator()(const Eigen::Vector3d& p) const { return A * p + b; }
};

Affine randomAffine(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Affine f;
  for (int r = 0; r < 2; ++r) {
    for (int c = 0; c < 3; ++c) f.A(r, c) = 1e-3 * u(rng);
    f.b[r] = 0.1 * u(rng);
  }
  return f;
}

TEST(ErrorGrid3d, ExactAtNodes) {
  std::mt19937 rng(test::kSeed);
  const Axes axes = sampleAxes();
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const ErrorGrid3d g =
      ErrorGrid3d::fromFunction(axes, [&](const Eigen::Vector3d&) -> Eigen::VectorXd {
        return Eigen::Vector3d(u(rng), u(rng), u(rng));
      });
  for (std::size_t k = 0; k < axes[2].size(); ++k)
    for (std::size_t j = 0; j < axes[1].size(); ++j)
      for (std::size_t i = 0; i < axes[0].size(); ++i)
        EXPECT_EQ(g.evaluate(g.nodePoint(i, j, k)),
                  g.values().row(g.nodeIndex(i, j, k)).transpose());
}

TEST(ErrorGrid3d, ExactForAffineFields) {
  std::mt19937 rng(test::kSeed);
  const Axes axes = sampleAxes();
  for (int trial = 0; trial < 5; ++trial) {
    const Affine f = randomAffine(rng);
    const ErrorGrid3d g = ErrorGrid3d::fromFunction(axes, f);
    for (int k = 0; k < 100; ++k) {
      const Eigen::Vector3d p = randomPoint(rng, axes);
      EXPECT_LT((g.evaluate(p) - f(p)).norm(), kTolExact) << p.transpose();
    }
  }
}

TEST(ErrorGrid3d, ExactForMultilinearFields) {
  std::mt19937 rng(test::kSeed);
  const Axes axes = sampleAxes();
  auto f = [](const Eigen::Vector3d& p) -> Eigen::VectorXd {
    return Eigen::VectorXd::Constant(
        1, 0.1 + 1e-7 * p.x() * p.y() - 2e-9 * p.x() * p.y() * p.z() + 1e-4 * p.z());
  };
  const ErrorGrid3d g = ErrorGrid3d::fromFunction(axes, f);
  for (int k = 0; k < 100; ++k) {
    const Eigen::Vector3d p = randomPoint(rng, axes);
    EXPECT_NEAR(g.evaluate(p)[0], f(p)[0], kTolExact);
  }
}

TEST(ErrorGrid3d, LinearAlongGridLines) {
  const Axes axes = sampleAxes();
  const ErrorGrid3d g =
      ErrorGrid3d::fromFunction(axes, [](const Eigen::Vector3d& p) -> Eigen::VectorXd {
        return Eigen::VectorXd::Constant(
            1, std::sin(p.x() / 100.0) + std::cos(p.y() / 70.0) * p.z() / 300.0);
      });
  // Along x between nodes (1, 2, 3) and (2, 2, 3), the value is linear in x.
  const Eigen::Vector3d a = g.nodePoint(1, 2, 3), b = g.nodePoint(2, 2, 3);
  const double va = g.evaluate(a)[0], vb = g.evaluate(b)[0];
  for (double f : {0.1, 0.5, 0.8})
    EXPECT_NEAR(g.evaluate(a + f * (b - a))[0], (1 - f) * va + f * vb, kTolExact);
}

TEST(ErrorGrid3d, ClampAndThrowOutsideTheGrid) {
  std::mt19937 rng(test::kSeed);
  const Axes axes = sampleAxes();
  const Affine f = randomAffine(rng);
  const ErrorGrid3d clamp = ErrorGrid3d::fromFunction(axes, f, OutOfRange::kClamp);
  const ErrorGrid3d strict = ErrorGrid3d::fromFunction(axes, f, OutOfRange::kThrow);
  const Eigen::Vector3d outside(400.0, -10.0, -150.0), clamped(350.0, -10.0, -100.0);
  EXPECT_LT((clamp.evaluate(outside) - f(clamped)).norm(), kTolExact);
  EXPECT_THROW((void)strict.evaluate(outside), InvalidArgument);
  EXPECT_NO_THROW((void)strict.evaluate(Eigen::Vector3d(350.0, -350.0, 300.0)));
  EXPECT_THROW((void)clamp.evaluate(Eigen::Vector3d(0.0, std::nan(""), 0.0)), InvalidArgument);
}

TEST(ErrorGrid3d, SingleNodeAxisIsConstantAlongIt) {
  const Axes axes = {
      std::vector<double>{0.0, 10.0}, std::vector<double>{5.0}, std::vector<double>{0.0, 1.0}};
  const ErrorGrid3d g =
      ErrorGrid3d::fromFunction(axes, [](const Eigen::Vector3d& p) -> Eigen::VectorXd {
        return Eigen::VectorXd::Constant(1, p.x() + 100.0 * p.z());
      });
  for (double y : {-50.0, 5.0, 80.0})
    EXPECT_NEAR(g.evaluate(Eigen::Vector3d(2.5, y, 0.5))[0], 52.5, kTolExact);
}

TEST(ErrorGrid3d, RejectsBadGrids) {
  const Axes good = sampleAxes();
  const Eigen::Index n = 5 * 4 * 5;
  EXPECT_NO_THROW(ErrorGrid3d(good, Eigen::MatrixXd::Zero(n, 6)));
  Axes empty = good;
  empty[1].clear();
  EXPECT_THROW(ErrorGrid3d(empty, Eigen::MatrixXd::Zero(0, 6)), InvalidArgument);
  Axes repeated = good;
  repeated[2][3] = repeated[2][2];
  EXPECT_THROW(ErrorGrid3d(repeated, Eigen::MatrixXd::Zero(n, 6)), InvalidArgument);
  Axes decreasing = good;
  std::swap(decreasing[0][0], decreasing[0][1]);
  EXPECT_THROW(ErrorGrid3d(decreasing, Eigen::MatrixXd::Zero(n, 6)), InvalidArgument);
  Axes nan_node = good;
  nan_node[0][2] = std::nan("");
  EXPECT_THROW(ErrorGrid3d(nan_node, Eigen::MatrixXd::Zero(n, 6)), InvalidArgument);
  EXPECT_THROW(ErrorGrid3d(good, Eigen::MatrixXd::Zero(n - 1, 6)), InvalidArgument);
  EXPECT_THROW(ErrorGrid3d(good, Eigen::MatrixXd::Zero(n, 0)), InvalidArgument);
  Eigen::MatrixXd nan_value = Eigen::MatrixXd::Zero(n, 6);
  nan_value(7, 2) = std::nan("");
  EXPECT_THROW(ErrorGrid3d(good, nan_value), InvalidArgument);
  int calls = 0;
  auto ragged = [&calls](const Eigen::Vector3d&) -> Eigen::VectorXd {
    return Eigen::VectorXd::Zero(++calls == 3 ? 5 : 6);
  };
  EXPECT_THROW((void)ErrorGrid3d::fromFunction(good, ragged), InvalidArgument);
  EXPECT_THROW(
      (void)ErrorGrid3d(good, Eigen::MatrixXd::Zero(n, 2)).evaluateMotion(Eigen::Vector3d::Zero()),
      InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::geometry
