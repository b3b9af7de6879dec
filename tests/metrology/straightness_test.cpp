#include "pkm/metrology/straightness.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace pkm::metrology {
namespace PKM_TEST_NS {

constexpr double kTolZone = 1e-12;      ///< zone widths of O(1) data compared in double precision
constexpr double kTolZoneLarge = 1e-9;  ///< zone widths of 1e6 points (rounding accumulates)
constexpr std::size_t kBruteForcePoints = 40;
constexpr std::size_t kLargePoints = 1'000'000;

/// Brute force: the zone width is convex and piecewise linear in the slope with breakpoints among
/// the slopes through pairs of points, so its minimum is the minimum over all those slopes.
double bruteForceZone(const std::vector<double>& x, const std::vector<double>& d) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < x.size(); ++i) {
    for (std::size_t j = 0; j < x.size(); ++j) {
      if (x[i] >= x[j]) continue;
      const double m = (d[j] - d[i]) / (x[j] - x[i]);
      double hi = -std::numeric_limits<double>::infinity(), lo = -hi;
      for (std::size_t k = 0; k < x.size(); ++k) {
        hi = std::max(hi, d[k] - m * x[k]);
        lo = std::min(lo, d[k] - m * x[k]);
      }
      best = std::min(best, hi - lo);
    }
  }
  return best;
}

/// Checks the Chebyshev certificate: three contacts sorted by position, the outer two on one zone
/// line and the middle one on the other, each residual at ± straightness/2.
void expectCertified(const StraightnessResult& r, const std::vector<double>& x, double tol) {
  ASSERT_EQ(r.contact_points.size(), 3u);
  const double half = 0.5 * r.straightness;
  const double first = r.residuals[r.contact_points[0]];
  EXPECT_NEAR(std::abs(first), half, tol);
  EXPECT_NEAR(r.residuals[r.contact_points[2]], first, tol);
  EXPECT_NEAR(r.residuals[r.contact_points[1]], -first, tol);
  EXPECT_LE(x[r.contact_points[0]], x[r.contact_points[1]]);
  EXPECT_LE(x[r.contact_points[1]], x[r.contact_points[2]]);
  EXPECT_LT(x[r.contact_points[0]], x[r.contact_points[2]]);
}

TEST(Straightness, HandComputedTriangle) {
  const std::vector<double> x{0.0, 1.0, 2.0}, d{0.0, 1.0, 0.0};
  const StraightnessResult ls = evaluateStraightness(x, d, StraightnessReference::kLeastSquares);
  EXPECT_NEAR(ls.line.slope, 0.0, kTolZone);
  EXPECT_NEAR(ls.line.intercept, 1.0 / 3.0, kTolZone);
  EXPECT_NEAR(ls.straightness, 1.0, kTolZone);
  const StraightnessResult ep = evaluateStraightness(x, d, StraightnessReference::kEndpoint);
  EXPECT_NEAR(ep.line.intercept, 0.0, kTolZone);
  EXPECT_NEAR(ep.straightness, 1.0, kTolZone);
  const StraightnessResult mz = evaluateStraightness(x, d, StraightnessReference::kMinimumZone);
  EXPECT_NEAR(mz.line.slope, 0.0, kTolZone);
  EXPECT_NEAR(mz.line.intercept, 0.5, kTolZone);
  EXPECT_NEAR(mz.straightness, 1.0, kTolZone);
  EXPECT_EQ(mz.contact_points, (std::vector<std::size_t>{0, 1, 2}));
  expectCertified(mz, x, kTolZone);
}

TEST(Straightness, ExactLineIsRecoveredByEveryReference) {
  std::vector<double> x, d;
  for (int k = 0; k < 9; ++k) {
    x.push_back(-50.0 + 37.0 * k);
    d.push_back(0.0125 - 2.5e-5 * x.back());
  }
  for (auto ref : {StraightnessReference::kEndpoint,
                   StraightnessReference::kLeastSquares,
                   StraightnessReference::kMinimumZone}) {
    const StraightnessResult r = evaluateStraightness(x, d, ref);
    EXPECT_NEAR(r.line.slope, -2.5e-5, test::kTolExact);
    EXPECT_NEAR(r.line.intercept, 0.0125, test::kTolExact);
    EXPECT_NEAR(r.straightness, 0.0, test::kTolExact);
  }
}

TEST(Straightness, MinimumZoneIsOptimalAndNeverWorseThanLeastSquaresOrEndpoint) {
  std::mt19937_64 rng(test::kSeed);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::uniform_real_distribution<double> pos(0.0, 500.0);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<double> x, d;
    for (std::size_t k = 0; k < kBruteForcePoints; ++k) {
      // Every fifth point repeats a position (several runs at one target).
      x.push_back(k % 5 == 4 ? x.back() : pos(rng));
      d.push_back(3e-3 * x.back() + 0.01 * std::sin(0.05 * x.back()) + 0.002 * noise(rng));
    }
    const StraightnessResult mz = evaluateStraightness(x, d, StraightnessReference::kMinimumZone);
    const StraightnessResult ls = evaluateStraightness(x, d, StraightnessReference::kLeastSquares);
    const StraightnessResult ep = evaluateStraightness(x, d, StraightnessReference::kEndpoint);
    EXPECT_LE(mz.straightness, ls.straightness + kTolZone);
    EXPECT_LE(mz.straightness, ep.straightness + kTolZone);
    EXPECT_NEAR(mz.straightness, bruteForceZone(x, d), kTolZone);
    expectCertified(mz, x, kTolZone);
    // Zone centred: max and min residual symmetric.
    const auto [lo, hi] = std::minmax_element(mz.residuals.begin(), mz.residuals.end());
    EXPECT_NEAR(*hi + *lo, 0.0, kTolZone);
  }
}

TEST(Straightness, LeastSquaresMatchesNormalEquations) {
  std::mt19937_64 rng(test::kSeed + 1);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<double> x, d;
  double sx = 0, sd = 0, sxx = 0, sxd = 0;
  for (int k = 0; k < 30; ++k) {
    x.push_back(10.0 * k);
    d.push_back(0.001 * noise(rng));
    sx += x.back();
    sd += d.back();
    sxx += x.back() * x.back();
    sxd += x.back() * d.back();
  }
  const double n = 30.0, den = n * sxx - sx * sx;  // closed forms of the least-squares line
  const ReferenceLine l = leastSquaresLine(x, d);
  EXPECT_NEAR(l.slope, (n * sxd - sx * sd) / den, test::kTolExact);
  EXPECT_NEAR(l.intercept, (sxx * sd - sx * sxd) / den, test::kTolExact);
}

TEST(Straightness, MillionPointsMinimumZone) {
  std::mt19937_64 rng(test::kSeed + 2);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> x(kLargePoints), d(kLargePoints);
  for (std::size_t k = 0; k < kLargePoints; ++k) {
    x[k] = 1000.0 * static_cast<double>(k) / static_cast<double>(kLargePoints);
    d[k] = 1e-4 * x[k] + 0.005 * u(rng);  // zone width just below 0.01 mm
  }
  const auto start = std::chrono::steady_clock::now();
  const StraightnessResult mz = evaluateStraightness(x, d, StraightnessReference::kMinimumZone);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  RecordProperty("minzone_1e6_seconds", std::to_string(seconds));
  std::printf("minimum zone of %zu points: %.3f s\n", kLargePoints, seconds);
  const StraightnessResult ls = evaluateStraightness(x, d, StraightnessReference::kLeastSquares);
  EXPECT_LE(mz.straightness, ls.straightness);
  EXPECT_LE(mz.straightness, 0.01);
  EXPECT_NEAR(mz.line.slope, 1e-4, 1e-6);
  expectCertified(mz, x, kTolZoneLarge);
}

TEST(Straightness, RejectsBadInput) {
  const std::vector<double> one{1.0}, two{1.0, 2.0}, same{3.0, 3.0};
  const std::vector<double> nan{0.0, std::nan("")};
  for (auto ref : {StraightnessReference::kEndpoint,
                   StraightnessReference::kLeastSquares,
                   StraightnessReference::kMinimumZone}) {
    EXPECT_THROW((void)evaluateStraightness(one, one, ref), InvalidArgument);
    EXPECT_THROW((void)evaluateStraightness(two, one, ref), InvalidArgument);
    EXPECT_THROW((void)evaluateStraightness(same, two, ref), InvalidArgument);
    EXPECT_THROW((void)evaluateStraightness(two, nan, ref), InvalidArgument);
    EXPECT_THROW((void)evaluateStraightness(nan, two, ref), InvalidArgument);
  }
  EXPECT_EQ(parseStraightnessReference("minzone"), StraightnessReference::kMinimumZone);
  EXPECT_EQ(toString(parseStraightnessReference("lsq")), "lsq");
  EXPECT_THROW((void)parseStraightnessReference("best"), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::metrology
