#include "pkm/calibration/parameter_budget.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "pkm/core/error.hpp"

namespace pkm::calibration {
namespace PKM_TEST_NS {

/// A straight line y = a + b·x through x = −1, 0, 1 (J = [1 x]): J⁺ = (JᵀJ)⁻¹Jᵀ with
/// JᵀJ = diag(3, 2), so δa = mean(δr), δb = (δr₃ − δr₁)/2.
Eigen::MatrixXd lineJacobian() {
  Eigen::MatrixXd J(3, 2);
  J << 1, -1, 1, 0, 1, 1;
  return J;
}

metrology::UncertaintyContributor rectangular(double half_width) {
  metrology::UncertaintyContributor c;
  c.name = "instrument";
  c.value = half_width;
  c.unit = "mm";
  c.distribution = metrology::Distribution::kRectangular;
  return c;
}

TEST(IdentificationInverse, IsThePseudoInverseOnTheIdentifiableSubspace) {
  const Eigen::MatrixXd J = lineJacobian();
  const Eigen::MatrixXd A = identificationInverse(J, 2, 3);
  const Eigen::MatrixXd expected = (J.transpose() * J).inverse() * J.transpose();
  EXPECT_TRUE(A.isApprox(expected, 1e-12));
  // A prior row below the observations: only the observation columns are returned.
  Eigen::MatrixXd Jp(4, 2);
  Jp << J, Eigen::RowVector2d(0.0, 1.0);
  EXPECT_EQ(identificationInverse(Jp, 2, 3).cols(), 3);
  // Rank 1: the weak direction (b, singular value √2 < √3) is dropped.
  const Eigen::MatrixXd A1 = identificationInverse(J, 1, 3);
  EXPECT_NEAR(A1.row(1).norm(), 0.0, 1e-12);
  EXPECT_THROW((void)identificationInverse(J, -1, 3), InvalidArgument);
  EXPECT_THROW((void)identificationInverse(J, 2, 4), InvalidArgument);
}

TEST(ParameterBudgets, LineFitByHand) {
  // Instrument: ±0.03 mm rectangular per reading → u = 0.03/√3 = 0.017320508 mm.
  // u(a) = u·‖(1/3, 1/3, 1/3)‖ = u/√3 = 0.01; u(b) = u·‖(−½, 0, ½)‖ = u/√2 = 0.012247449.
  // Residual σ 0.02 mm: σ_A = √(0.02² − 0.017320508²) = √(0.0004 − 0.0003) = 0.01 mm;
  // its contributions: σ_A/√3 = 0.0057735 (a) and σ_A/√2 = 0.0070711 (b).
  ParameterBudgetInput in;
  in.names = {"a", "b"};
  in.units = {"mm", "1"};
  in.values = Eigen::Vector2d(1.0, 0.5);
  in.inverse = identificationInverse(lineJacobian(), 2, 3);
  in.residual_sigma = 0.02;
  in.sources.push_back({rectangular(0.03), Eigen::MatrixXd::Identity(3, 3).sparseView()});
  const ParameterUncertainty p = parameterBudgets(in);
  ASSERT_EQ(p.budgets.size(), 2u);
  EXPECT_NEAR(p.instrument_sigma, 0.017320508, 1e-9);
  EXPECT_NEAR(p.fit_sigma, 0.01, 1e-9);
  const metrology::UncertaintyBudget& a = p.budgets[0];
  ASSERT_EQ(a.contributors.size(), 2u);
  EXPECT_EQ(a.quantity, "a");
  EXPECT_DOUBLE_EQ(a.value, 1.0);
  EXPECT_NEAR(a.contributors[0].contribution(), 0.01, 1e-9);
  EXPECT_NEAR(a.contributors[1].contribution(), 0.0057735027, 1e-9);
  EXPECT_NEAR(a.expandedUncertainty(), 2.0 * std::hypot(0.01, 0.0057735027), 1e-9);
  const metrology::UncertaintyBudget& b = p.budgets[1];
  EXPECT_NEAR(b.contributors[0].contribution(), 0.012247449, 1e-9);
  EXPECT_NEAR(b.contributors[1].contribution(), 0.0070710678, 1e-9);
  // The covariance's diagonal is u_c²; a and b are uncorrelated here (x centred).
  EXPECT_NEAR(p.covariance(0, 0), std::pow(a.combinedStandardUncertainty(), 2), 1e-15);
  EXPECT_NEAR(p.covariance(1, 1), std::pow(b.combinedStandardUncertainty(), 2), 1e-15);
  EXPECT_NEAR(p.covariance(0, 1), 0.0, 1e-15);
}

TEST(ParameterBudgets, ScatterBelowTheInstrumentAddsNoTypeAContributor) {
  ParameterBudgetInput in;
  in.names = {"a", "b"};
  in.units = {"mm", "1"};
  in.values = Eigen::Vector2d::Zero();
  in.inverse = identificationInverse(lineJacobian(), 2, 3);
  in.residual_sigma = 0.01;  // below the instrument's 0.0173
  in.sources.push_back({rectangular(0.03), Eigen::MatrixXd::Identity(3, 3).sparseView()});
  const ParameterUncertainty p = parameterBudgets(in);
  EXPECT_EQ(p.fit_sigma, 0.0);
  EXPECT_EQ(p.budgets[0].contributors.size(), 1u);  // zero contributions are not listed
}

TEST(ParameterBudgets, RejectsInconsistentInput) {
  ParameterBudgetInput in;
  in.names = {"a"};
  in.units = {"mm"};
  in.values = Eigen::VectorXd::Zero(1);
  in.inverse = Eigen::MatrixXd::Zero(2, 3);
  std::string why;
  EXPECT_FALSE(in.isValid(&why));
  EXPECT_NE(why.find("must agree"), std::string::npos);
  EXPECT_THROW((void)parameterBudgets(in), InvalidArgument);
  in.inverse = Eigen::MatrixXd::Zero(1, 3);
  in.sources.push_back({rectangular(1.0), Eigen::MatrixXd::Identity(2, 2).sparseView()});
  EXPECT_FALSE(in.isValid(&why));
  EXPECT_NE(why.find("instrument"), std::string::npos);
  in.sources.clear();
  in.coverage_factor = 0.0;
  EXPECT_FALSE(in.isValid());
}

TEST(PositionExpandedUncertainty, IsKTimesTheLargestStandardDeviation) {
  // J = I: the covariance diag(4, 1, 9) µm² → worst direction z, u = 3, U = 6.
  const Eigen::Matrix3d J = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d S = Eigen::Vector3d(4, 1, 9).asDiagonal();
  EXPECT_NEAR(positionExpandedUncertainty(J, S, 2.0), 6.0, 1e-12);
  // Two parameters acting on x only: u_x² = 1 + 1 → U = 2√2.
  Eigen::MatrixXd J2 = Eigen::MatrixXd::Zero(3, 2);
  J2(0, 0) = J2(0, 1) = 1.0;
  EXPECT_NEAR(positionExpandedUncertainty(J2, Eigen::Matrix2d::Identity(), 2.0),
              2.0 * std::sqrt(2.0),
              1e-12);
  EXPECT_THROW((void)positionExpandedUncertainty(J2, S, 2.0), InvalidArgument);
  EXPECT_THROW((void)positionExpandedUncertainty(J, S, 0.0), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration
