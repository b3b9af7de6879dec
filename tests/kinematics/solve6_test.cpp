// Tests of the internal fixed-size solver src/kinematics/detail/solve6.hpp against Eigen.
#include "kinematics/detail/solve6.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <random>

#include "support/tolerances.hpp"

namespace pkm::kinematics::detail {
namespace PKM_TEST_NS {

using M6 = Eigen::Matrix<double, 6, 6>;
using V6 = Eigen::Matrix<double, 6, 1>;

/// A·x = b as forward kinematics solves it: factor6, then substitute6 when not singular (b is
/// left as it was otherwise); factor6's pivot ratio.
double solve6(const M6& A, V6& b, int* det_sign = nullptr) {
  Lu6 lu;
  const double ratio = factor6(A, lu, det_sign);
  if (lu.valid) substitute6(lu, b);
  return ratio;
}

TEST(Solve6, MatchesEigenOnRandomSystems) {
  std::mt19937 rng(test::kSeed);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 200; ++k) {
    M6 A;
    V6 b;
    for (int i = 0; i < 36; ++i) A.data()[i] = u(rng);
    for (int i = 0; i < 6; ++i) b[i] = u(rng);
    const V6 expected = A.fullPivLu().solve(b);
    M6 work = A;
    V6 x = b;
    const double ratio = solve6(work, x);
    EXPECT_GT(ratio, 0.0);
    EXPECT_LT((x - expected).norm(), 1e-9 * (1 + expected.norm()));
    EXPECT_LT((A * x - b).norm(), 1e-10);
  }
}

TEST(Solve6, ScaledColumnsFactoriseAsTheScaledMatrix) {
  // factor6 with right_scale s factorises A·diag(1, 1, 1, s, s, s): the same factorisation, bit
  // for bit, as of the matrix scaled beforehand (what forward kinematics used to copy).
  std::mt19937 rng(test::kSeed + 7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < 100; ++k) {
    M6 A;
    for (int i = 0; i < 36; ++i) A.data()[i] = u(rng);
    const double scale = 0.05 + std::abs(u(rng));
    M6 scaled = A;
    scaled.rightCols<3>() *= scale;
    Lu6 a, b;
    int sign_a = 0, sign_b = 0;
    EXPECT_EQ(factor6(A, a, &sign_a, scale), factor6(scaled, b, &sign_b));
    EXPECT_EQ(sign_a, sign_b);
    EXPECT_EQ(a.m, b.m);
    EXPECT_EQ(a.row, b.row);
    EXPECT_EQ(a.inverse_pivot, b.inverse_pivot);
  }
}

TEST(Solve6, DeterminantSignMatchesEigen) {
  std::mt19937 rng(test::kSeed + 1);
  std::uniform_real_distribution<double> u(-1, 1);
  int negative = 0;
  for (int k = 0; k < 500; ++k) {
    M6 A;
    for (int i = 0; i < 36; ++i) A.data()[i] = u(rng);
    V6 x = V6::Ones();
    int sign = 0;
    ASSERT_GT(solve6(A, x, &sign), 0.0);
    const double det = A.determinant();
    EXPECT_EQ(sign, det > 0.0 ? 1 : -1) << det;
    negative += sign < 0;
  }
  EXPECT_GT(negative, 100);  // both signs were met
  V6 b = V6::Ones();
  int sign = 7;
  EXPECT_EQ(solve6(M6::Zero(), b, &sign), 0.0);
  EXPECT_EQ(sign, 0);
}

TEST(Solve6, NeedsPivotingWhenLeadingEntryIsZero) {
  M6 A = M6::Identity();
  A.row(0).swap(A.row(3));  // a permutation matrix: zero on the first diagonal entry
  V6 b;
  b << 1, 2, 3, 4, 5, 6;
  const V6 expected = A.transpose() * b;
  V6 x = b;
  M6 work = A;
  EXPECT_EQ(solve6(work, x), 1.0);
  EXPECT_LT((x - expected).norm(), test::kTolExact);
}

TEST(Solve6, SingularMatrixGivesZeroOrTinyPivotRatio) {
  M6 A = M6::Identity();
  A.row(5) = A.row(4);
  V6 b = V6::Ones();
  EXPECT_EQ(solve6(A, b), 0.0);
  M6 B = M6::Identity();
  B(5, 5) = 1e-15;
  V6 c = V6::Ones();
  EXPECT_LT(solve6(B, c), 1e-12);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::kinematics::detail
