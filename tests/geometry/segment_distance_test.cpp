#include "pkm/geometry/segment_distance.hpp"

#include <random>

#include <gtest/gtest.h>

#include "support/tolerances.hpp"

namespace pkm::geometry {
namespace {

using V = Eigen::Vector3d;

/// Brute force over a fine grid plus local refinement (independent of the closed form).
double bruteForce(const V& p0, const V& p1, const V& q0, const V& q1) {
  double best = INFINITY;
  constexpr int n = 400;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      best = std::min(best, ((p0 + (p1 - p0) * i / double(n)) - (q0 + (q1 - q0) * j / double(n))).norm());
  return best;
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
  EXPECT_NEAR(segmentDistance(V(0, 0, 0), V(2, 0, 0), V(1, 3, 0), V(5, 3, 0)).distance, 3.0, test::kTolExact);
  EXPECT_NEAR(segmentDistance(V(0, 0, 0), V(2, 0, 0), V(4, 3, 0), V(6, 3, 0)).distance, std::sqrt(13.0),
              test::kTolExact);
}

TEST(SegmentDistance, DegenerateSegments) {
  EXPECT_NEAR(segmentDistance(V(0, 0, 0), V(0, 0, 0), V(1, 1, 0), V(1, 1, 0)).distance, std::sqrt(2.0),
              test::kTolExact);
  EXPECT_NEAR(segmentDistance(V(0, 2, 0), V(0, 2, 0), V(-1, 0, 0), V(1, 0, 0)).distance, 2.0, test::kTolExact);
  EXPECT_NEAR(segmentDistance(V(-1, 0, 0), V(1, 0, 0), V(0, 0, 5), V(0, 0, 5)).distance, 5.0, test::kTolExact);
}

TEST(SegmentDistance, MatchesBruteForceOnRandomSegments) {
  std::mt19937 rng(test::kSeed);
  std::uniform_real_distribution<double> u(-1, 1);
  auto rv = [&] { return V(u(rng), u(rng), u(rng)); };
  for (int k = 0; k < 40; ++k) {
    const V p0 = rv(), p1 = rv(), q0 = rv(), q1 = rv();
    const auto d = segmentDistance(p0, p1, q0, q1);
    EXPECT_LE(d.distance, bruteForce(p0, p1, q0, q1) + 1e-12);
    EXPECT_GE(d.distance, bruteForce(p0, p1, q0, q1) - 2e-2);  // grid resolution
    EXPECT_NEAR((d.p - d.q).norm(), d.distance, test::kTolExact);
    EXPECT_GE(d.s, 0.0);
    EXPECT_LE(d.t, 1.0);
  }
}

}  // namespace
}  // namespace pkm::geometry
