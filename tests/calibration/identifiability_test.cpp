#include "pkm/calibration/identifiability.hpp"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>
#include <random>

#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace pkm::calibration {
namespace PKM_TEST_NS {

TEST(Identifiability, FullRankMatrix) {
  std::mt19937 rng(test::kSeed);
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::MatrixXd J(20, 4);
  for (Eigen::Index i = 0; i < J.size(); ++i) J.data()[i] = n(rng);
  const Identifiability id = analyseIdentifiability(J, {"a", "b", "c", "d"});
  EXPECT_EQ(id.rank, 4);
  EXPECT_TRUE(id.fullRank());
  EXPECT_EQ(id.null_space.cols(), 0);
  EXPECT_TRUE(id.combinations.empty());
  EXPECT_GE(id.condition_number, 1.0);
}

TEST(Identifiability, NamesTheUnidentifiableCombination) {
  // Columns a and b enter only as their sum (in different units: b scaled by 1000), and d is
  // never seen: two null-space directions.
  std::mt19937 rng(test::kSeed + 1);
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::MatrixXd J(30, 4);
  for (Eigen::Index r = 0; r < J.rows(); ++r) {
    const double s = n(rng);
    J(r, 0) = s;
    J(r, 1) = 1000.0 * s;
    J(r, 2) = n(rng);
    J(r, 3) = 0.0;
  }
  const Identifiability id = analyseIdentifiability(J, {"a", "b", "c", "d"});
  EXPECT_EQ(id.rank, 2);
  ASSERT_EQ(id.null_space.cols(), 2);
  // Every null-space vector v satisfies J·v = 0 in unscaled parameters.
  EXPECT_LT((J * id.null_space).cwiseAbs().maxCoeff(), test::kTolRoundTrip * 1e3);
  bool found_d = false, found_ab = false;
  for (const auto& combo : id.combinations) {
    if (combo.terms.size() == 1 && combo.terms[0].first == "d") found_d = true;
    if (combo.terms.size() == 2) found_ab = true;
  }
  EXPECT_TRUE(found_d);
  EXPECT_TRUE(found_ab);
}

TEST(Identifiability, NullSpaceReportDoesNotTurnWithTheSvdsBasis) {
  // A three-dimensional null space (e, f, g enter only as e + f, and h, i only as h − 2i in the
  // other units): J and Q·J (Q orthogonal: the same column norms, the same null space) make the
  // SVD return different bases for the repeated zero singular value; the reported directions are
  // the canonical ones, the same for both to rounding, orthonormal and in the null space.
  std::mt19937 rng(test::kSeed + 2);
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::MatrixXd J(40, 7);
  for (Eigen::Index r = 0; r < J.rows(); ++r) {
    const double s = n(rng), t = n(rng);
    J.row(r) << n(rng), s, s, t, -0.5 * t, n(rng), 0.0;
  }
  const std::vector<std::string> names{"a", "e", "f", "h", "i", "c", "z"};
  const Eigen::MatrixXd Q =
      Eigen::HouseholderQR<Eigen::MatrixXd>(Eigen::MatrixXd::NullaryExpr(40, 40, [&] {
        return n(rng);
      })).householderQ();
  const Identifiability a = analyseIdentifiability(J, names);
  const Identifiability b = analyseIdentifiability(Q * J, names);
  ASSERT_EQ(a.rank, 4);
  ASSERT_EQ(b.rank, 4);
  EXPECT_LT((a.null_space - b.null_space).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((J * a.null_space).cwiseAbs().maxCoeff(), 1e-12);
  ASSERT_EQ(a.combinations.size(), b.combinations.size());
  for (std::size_t k = 0; k < a.combinations.size(); ++k) {
    ASSERT_EQ(a.combinations[k].terms.size(), b.combinations[k].terms.size()) << k;
    for (std::size_t t = 0; t < a.combinations[k].terms.size(); ++t) {
      EXPECT_EQ(a.combinations[k].terms[t].first, b.combinations[k].terms[t].first);
      EXPECT_NEAR(a.combinations[k].terms[t].second, b.combinations[k].terms[t].second, 1e-12);
    }
  }
  // The canonical directions: e − f, h + 2i in the scaled (unit-column) space, and z alone.
  ASSERT_EQ(a.combinations.size(), 3u);
  EXPECT_EQ(a.combinations[0].terms.size(), 2u);
  EXPECT_EQ(a.combinations[0].terms[0].first, "e");
  EXPECT_NEAR(a.combinations[0].terms[0].second, std::sqrt(0.5), 1e-12);
  EXPECT_EQ(a.combinations[2].terms.size(), 1u);
  EXPECT_EQ(a.combinations[2].terms[0].first, "z");
}

TEST(Identifiability, RejectsBadInput) {
  EXPECT_THROW((void)analyseIdentifiability(Eigen::MatrixXd(0, 2), {"a", "b"}), InvalidArgument);
  EXPECT_THROW((void)analyseIdentifiability(Eigen::MatrixXd::Ones(3, 2), {"a"}), InvalidArgument);
  Eigen::MatrixXd J = Eigen::MatrixXd::Ones(3, 2);
  J(1, 1) = std::nan("");
  EXPECT_THROW((void)analyseIdentifiability(J, {"a", "b"}), InvalidArgument);
}

TEST(ObservabilityIndices, ClosedForms) {
  const Eigen::Vector3d s(4.0, 2.0, 1.0);
  const Eigen::Index m = 16;
  EXPECT_NEAR(observabilityIndex(ObservabilityIndex::kO1, s, m), 2.0 / 4.0, test::kTolExact);
  EXPECT_NEAR(observabilityIndex(ObservabilityIndex::kO2, s, m), 0.25, test::kTolExact);
  EXPECT_NEAR(observabilityIndex(ObservabilityIndex::kO3, s, m), 1.0, test::kTolExact);
  EXPECT_NEAR(observabilityIndex(ObservabilityIndex::kO4, s, m), 0.25, test::kTolExact);
  EXPECT_NEAR(observabilityIndex(ObservabilityIndex::kO5, s, m), 1.0 / 1.75, test::kTolExact);
  EXPECT_EQ(observabilityIndex(ObservabilityIndex::kO3, Eigen::Vector2d(1.0, 0.0), m), 0.0);
  EXPECT_EQ(parseObservabilityIndex("o4"), ObservabilityIndex::kO4);
  EXPECT_STREQ(toString(ObservabilityIndex::kO5), "O5");
  EXPECT_THROW((void)parseObservabilityIndex("O6"), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration
