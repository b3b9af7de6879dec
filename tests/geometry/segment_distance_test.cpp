#include "pkm/geometry/segment_distance.hpp"

#include <gtest/gtest.h>

#include <random>

#include "support/tolerances.hpp"

namespace pkm::geometry {
namespace PKM_TEST_NS {

using V = Eigen::Vector3d;

/// Independent minimum: nested ternary searches. |p(s) - q(t)|^2 is jointly convex, so
/// g(s) = min_t |p(s) - q(t)|^2 is convex and both searches converge to the global minimum.
double ternaryMin(const V& p0, const V& p1, const V& q0, const V& q1) {
  // 70 steps shrink [0, 1] by (2/3)^70 ≈ 5e-13: far below the 1e-7 the test asks of the distance.
  auto ternary = [](auto&& f) {
    double lo = 0.0, hi = 1.0;
    for (int k = 0; k < 70; ++k) {
      const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
      if (f(m1) <= f(m2))
        hi = m2;
      else
        lo = m1;
    }
    return f(0.5 * (lo + hi));
  };
  auto g = [&](double s) {
    const V p = p0 + s * (p1 - p0);
    return ternary([&](double t) { return (p - (q0 + t * (q1 - q0))).squaredNorm(); });
  };
  return std::sqrt(ternary(g));
}

TEST(SegmentDistance, CrossingSkewLines) {
  const auto d = segmentDistance(V(-1, 0, 0), V(1, 0, 0), V(0, -1, 2), V(0, 1, 2));
  EXPECT_NEAR(d.distance, 2.0, test::kTolExact);
  EXPECT_NEAR(d.s, 0.5, test::kTolExact);
  EXPECT_NEAR(d.t, 0.5, test::kTolExact);
}

TEST(SegmentDistance, EndpointRegion) {
  const auto d = segmentDistance(V(0, 0, 0), V(1, 0, 0), V(2, 1, 0), V(3, 5, 0));
  EXPECT_NEAR(d.distance, std::sqrt(2.0), test::kTolExact);
  EXPECT_EQ(d.s, 1.0);
  EXPECT_EQ(d.t, 0.0);
}

TEST(SegmentDistance, ParallelAndOverlapping) {
  EXPECT_NEAR(segmentDistance(V(0, 0, 0), V(2, 0, 0), V(1, 3, 0), V(5, 3, 0)).distance,
              3.0,
              test::kTolExact);
  EXPECT_NEAR(segmentDistance(V(0, 0, 0), V(2, 0, 0), V(4, 3, 0), V(6, 3, 0)).distance,
              std::sqrt(13.0),
              test::kTolExact);
}

TEST(SegmentDistance, DegenerateSegments) {
  EXPECT_NEAR(segmentDistance(V(0, 0, 0), V(0, 0, 0), V(1, 1, 0), V(1, 1, 0)).distance,
              std::sqrt(2.0),
              test::kTolExact);
  EXPECT_NEAR(segmentDistance(V(0, 2, 0), V(0, 2, 0), V(-1, 0, 0), V(1, 0, 0)).distance,
              2.0,
              test::kTolExact);
  EXPECT_NEAR(segmentDistance(V(-1, 0, 0), V(1, 0, 0), V(0, 0, 5), V(0, 0, 5)).distance,
              5.0,
              test::kTolExact);
}

TEST(SegmentDistance, MatchesIndependentSearchOnRandomSegments) {
  std::mt19937 rng(test::kSeed);
  std::uniform_real_distribution<double> u(-1, 1);
  auto rv = [&] { return V(u(rng), u(rng), u(rng)); };
  for (int k = 0; k < 60; ++k) {
    const V p0 = rv(), p1 = rv(), q0 = rv(), q1 = rv();
    const auto d = segmentDistance(p0, p1, q0, q1);
    EXPECT_NEAR(d.distance, ternaryMin(p0, p1, q0, q1), 1e-7);  // sqrt of a ~1e-15 search error
    EXPECT_NEAR((d.p - d.q).norm(), d.distance, test::kTolExact);
    EXPECT_GE(d.s, 0.0);
    EXPECT_LE(d.t, 1.0);
  }
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::geometry
