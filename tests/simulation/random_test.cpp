// RandomStream and streamSeed: determinism, independence of named streams, and the distribution of
// the uniform and normal variates.
#include "pkm/simulation/random.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "pkm/core/error.hpp"
#include "support/statistics.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

using pkm::simulation::RandomStream;
using pkm::simulation::streamSeed;
constexpr std::size_t kSamples = 200000;

TEST(Random, SameSeedSameSequence) {
  RandomStream a(pkm::test::kSeed), b(pkm::test::kSeed);
  for (int i = 0; i < 1000; ++i) {
    ASSERT_EQ(a.normal(), b.normal());
    ASSERT_EQ(a.uniform(), b.uniform());
  }
}

TEST(Random, StreamSeedDependsOnSeedAndName) {
  EXPECT_EQ(streamSeed(1, "linear-x"), streamSeed(1, "linear-x"));
  EXPECT_NE(streamSeed(1, "linear-x"), streamSeed(1, "linear-y"));
  EXPECT_NE(streamSeed(1, "linear-x"), streamSeed(2, "linear-x"));
  EXPECT_NE(streamSeed(0, ""), streamSeed(1, ""));
  RandomStream a(7, "a"), b(7, "b");
  EXPECT_NE(a.uniform(), b.uniform());
}

TEST(Random, GoldenValuesPinTheAlgorithm) {
  // mt19937_64 is fixed by the standard; these values change only if the transforms change.
  RandomStream r(42);
  std::mt19937_64 engine(42);
  const std::uint64_t first = engine();
  EXPECT_EQ(r.uniform(), static_cast<double>(first >> 11) / 9007199254740992.0);
  EXPECT_EQ(streamSeed(0, ""), streamSeed(0, ""));
}

TEST(Random, UniformIsInRangeWithTheRightMoments) {
  RandomStream r(pkm::test::kSeed);
  std::vector<double> v;
  for (std::size_t i = 0; i < kSamples; ++i) {
    const double u = r.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    v.push_back(u);
  }
  const double sigma = std::sqrt(1.0 / 12.0);
  EXPECT_NEAR(pkm::test::sampleMean(v), 0.5, pkm::test::meanTolerance(kSamples, sigma));
  EXPECT_NEAR(pkm::test::sampleSigma(v), sigma, sigma * pkm::test::sigmaRatioTolerance(kSamples));
  EXPECT_THROW((void)r.uniform(1.0, 0.0), pkm::InvalidArgument);
  const double x = r.uniform(-2.0, 3.0);
  EXPECT_GE(x, -2.0);
  EXPECT_LT(x, 3.0);
}

TEST(Random, NormalHasMeanZeroSigmaOneAndNormalTails) {
  RandomStream r(pkm::test::kSeed);
  std::vector<double> v;
  std::size_t beyond2 = 0;
  for (std::size_t i = 0; i < kSamples; ++i) {
    v.push_back(r.normal());
    if (std::abs(v.back()) > 2.0) ++beyond2;
  }
  EXPECT_NEAR(pkm::test::sampleMean(v), 0.0, pkm::test::meanTolerance(kSamples, 1.0));
  EXPECT_NEAR(pkm::test::sampleSigma(v), 1.0, pkm::test::sigmaRatioTolerance(kSamples));
  // P(|z| > 2) = 0.0455 for a normal distribution; binomial standard error.
  const double p = 0.0455;
  const double n = static_cast<double>(kSamples);
  EXPECT_NEAR(static_cast<double>(beyond2) / n, p, pkm::test::kStatZ * std::sqrt(p * (1 - p) / n));
}

TEST(Random, ZeroSigmaDrawsNothing) {
  RandomStream a(3), b(3);
  EXPECT_EQ(a.normal(0.0), 0.0);
  EXPECT_EQ(a.normal(), b.normal());
  EXPECT_THROW((void)a.normal(-1.0), pkm::InvalidArgument);
}

}  // namespace PKM_TEST_NS
