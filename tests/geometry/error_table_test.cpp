#include "pkm/geometry/error_table.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace pkm::geometry {
namespace PKM_TEST_NS {

using test::kTolExact;

/// Uneven node spacing (as ISO 230-2 recommends) and random values in two columns.
ErrorTable1d sampleTable(OutOfRange policy = OutOfRange::kClamp) {
  std::mt19937 rng(test::kSeed);
  std::uniform_real_distribution<double> u(-0.1, 0.1);
  const std::vector<double> positions = {
      -875.0, -760.5, -623.0, -500.0, -371.25, -250.0, -118.0, 0.0};
  Eigen::MatrixXd values(static_cast<Eigen::Index>(positions.size()), 2);
  for (Eigen::Index i = 0; i < values.rows(); ++i) values.row(i) << u(rng), u(rng);
  return ErrorTable1d(positions, values, policy);
}

TEST(ErrorTable1d, ExactAtNodes) {
  const ErrorTable1d t = sampleTable();
  for (std::size_t i = 0; i < t.positions().size(); ++i) {
    const Eigen::VectorXd v = t.evaluate(t.positions()[i]);
    EXPECT_EQ(v, t.values().row(static_cast<Eigen::Index>(i)).transpose()) << "node " << i;
  }
}

TEST(ErrorTable1d, LinearBetweenNodes) {
  const ErrorTable1d t = sampleTable();
  const auto& p = t.positions();
  for (std::size_t i = 0; i + 1 < p.size(); ++i) {
    const Eigen::Index r = static_cast<Eigen::Index>(i);
    for (double f : {0.25, 0.5, 0.9}) {
      const double s = p[i] + f * (p[i + 1] - p[i]);
      const Eigen::VectorXd expected =
          ((1 - f) * t.values().row(r) + f * t.values().row(r + 1)).transpose();
      EXPECT_LT((t.evaluate(s) - expected).norm(), kTolExact);
    }
  }
}

TEST(ErrorTable1d, ReproducesAffineFunctions) {
  const std::vector<double> p = {-3.0, -1.0, 0.5, 4.0, 4.5};
  Eigen::MatrixXd v(5, 1);
  for (Eigen::Index i = 0; i < 5; ++i) v(i, 0) = 2.0 - 0.75 * p[static_cast<std::size_t>(i)];
  const ErrorTable1d t(p, v);
  for (double s = -3.0; s <= 4.5; s += 0.37)
    EXPECT_NEAR(t.evaluate(s)[0], 2.0 - 0.75 * s, kTolExact);
}

TEST(ErrorTable1d, ClampHoldsEndValues) {
  const ErrorTable1d t = sampleTable(OutOfRange::kClamp);
  EXPECT_EQ(t.evaluate(-1e4), t.values().row(0).transpose());
  EXPECT_EQ(t.evaluate(10.0), t.values().row(t.values().rows() - 1).transpose());
}

TEST(ErrorTable1d, ThrowPolicyRejectsOutsideButAcceptsEnds) {
  const ErrorTable1d t = sampleTable(OutOfRange::kThrow);
  EXPECT_THROW((void)t.evaluate(-875.001), InvalidArgument);
  EXPECT_THROW((void)t.evaluate(1e-9), InvalidArgument);
  EXPECT_NO_THROW((void)t.evaluate(-875.0));
  EXPECT_NO_THROW((void)t.evaluate(0.0));
}

TEST(ErrorTable1d, NanQueryThrowsWhateverThePolicy) {
  EXPECT_THROW((void)sampleTable(OutOfRange::kClamp).evaluate(std::nan("")), InvalidArgument);
  EXPECT_THROW((void)sampleTable(OutOfRange::kThrow).evaluate(std::nan("")), InvalidArgument);
}

TEST(ErrorTable1d, SingleNodeIsConstant) {
  const ErrorTable1d t({5.0}, Eigen::MatrixXd::Constant(1, 3, 0.25));
  EXPECT_EQ(t.evaluate(-100.0), Eigen::VectorXd::Constant(3, 0.25));
  EXPECT_EQ(t.evaluate(5.0), Eigen::VectorXd::Constant(3, 0.25));
}

TEST(ErrorTable1d, RejectsBadTables) {
  const Eigen::MatrixXd three = Eigen::MatrixXd::Zero(3, 6);
  const double nan = std::nan(""), inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(ErrorTable1d({}, Eigen::MatrixXd::Zero(0, 6)), InvalidArgument);  // empty
  EXPECT_THROW(ErrorTable1d({0.0, 1.0, 1.0}, three), InvalidArgument);           // repeated
  EXPECT_THROW(ErrorTable1d({0.0, 2.0, 1.0}, three), InvalidArgument);           // decreasing
  EXPECT_THROW(ErrorTable1d({0.0, nan, 2.0}, three), InvalidArgument);           // NaN position
  EXPECT_THROW(ErrorTable1d({0.0, 1.0, inf}, three), InvalidArgument);           // infinite
  EXPECT_THROW(ErrorTable1d({0.0, 1.0}, three), InvalidArgument);                // row count
  EXPECT_THROW(ErrorTable1d({0.0, 1.0, 2.0}, Eigen::MatrixXd::Zero(3, 0)),
               InvalidArgument);  // no columns
  Eigen::MatrixXd bad = three;
  bad(1, 4) = nan;
  EXPECT_THROW(ErrorTable1d({0.0, 1.0, 2.0}, bad), InvalidArgument);  // NaN value
  EXPECT_THROW((void)ErrorTable1d::fromErrorMotions({0.0, 1.0}, {ErrorMotion::Zero()}),
               InvalidArgument);
}

TEST(ErrorTable1d, ErrorMotionTables) {
  ErrorMotion a = ErrorMotion::Zero(), b = ErrorMotion::Zero();
  a[kDx] = -0.078;
  b[kEy] = -0.069e-3;
  const ErrorTable1d t = ErrorTable1d::fromErrorMotions({-875.0, 0.0}, {a, b});
  EXPECT_EQ(t.components(), 6);
  EXPECT_LT((t.evaluateMotion(-437.5) - 0.5 * (a + b)).norm(), kTolExact);
  EXPECT_THROW((void)sampleTable().evaluateMotion(0.0), InvalidArgument);  // two columns, not six
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::geometry
