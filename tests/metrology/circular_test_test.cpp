#include "pkm/metrology/circular_test.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace pkm::metrology {
namespace PKM_TEST_NS {

constexpr double kTolCircular = 1e-9;  ///< G, G(b), H, F of synthetic paths, mm

/// r(θ) = R + a·cos 2θ + shift sampled at n equal angles about c (an oval path: no eccentricity,
/// so the LSC centre is c by symmetry).
std::vector<Point2> ovalPath(const Point2& c, double r, double a, double shift, int n, bool cw) {
  std::vector<Point2> p;
  for (int k = 0; k < n; ++k) {
    const double t = (cw ? -1.0 : 1.0) * 2.0 * std::numbers::pi * k / n;
    p.emplace_back(c + (r + a * std::cos(2.0 * t) + shift) * Point2(std::cos(t), std::sin(t)));
  }
  return p;
}

TEST(CircularTest, OvalWithHysteresisGivesClosedFormGAndH) {
  const Point2 c(10.0, -5.0);
  const double r = 150.0, a = 0.004, delta = 0.0015;
  const auto cw = ovalPath(c, r, a, 0.0, 360, true);
  const auto ccw = ovalPath(c, r, a, delta, 360, false);
  CircularTestOptions opt;
  opt.nominal_radius = r;
  opt.nominal_center = c;
  const CircularTestResult res = evaluateCircularTest(cw, ccw, opt);
  EXPECT_EQ(res.centre, CircularCentre::kLeastSquares);
  EXPECT_NEAR(res.cw.circular_deviation, 2.0 * a, kTolCircular);  // G (ISO 230-4 3.2)
  EXPECT_NEAR(res.ccw.circular_deviation, 2.0 * a, kTolCircular);
  EXPECT_NEAR(res.bidirectional_deviation, 2.0 * a + delta, kTolCircular);  // G(b)
  EXPECT_NEAR(res.hysteresis, delta, kTolCircular);                         // H (3.3)
  EXPECT_NEAR((res.common_center - c).norm(), 0.0, kTolCircular);
  EXPECT_NEAR(*res.cw.radial_deviation_max, a, kTolCircular);  // F (3.4)
  EXPECT_NEAR(*res.cw.radial_deviation_min, -a, kTolCircular);
  EXPECT_NEAR(*res.ccw.mean_radial_deviation, delta, kTolCircular);
}

TEST(CircularTest, MinimumZoneCentreIsNeverWorse) {
  auto cw = ovalPath(Point2::Zero(), 50.0, 0.002, 0.0, 90, true);
  for (std::size_t k = 0; k < cw.size(); k += 7) cw[k] *= 1.0 + 2e-5;  // spikes
  const auto ccw = ovalPath(Point2::Zero(), 50.0, 0.002, 0.0005, 90, false);
  CircularTestOptions lsc;
  CircularTestOptions mzc;
  mzc.centre = CircularCentre::kMinimumZone;
  const auto a = evaluateCircularTest(cw, ccw, lsc);
  const auto b = evaluateCircularTest(cw, ccw, mzc);
  EXPECT_LE(b.cw.circular_deviation, a.cw.circular_deviation + kTolCircular);
  EXPECT_LE(b.bidirectional_deviation, a.bidirectional_deviation + kTolCircular);
}

TEST(CircularTest, HysteresisSkipsAnglesWithoutOverlap) {
  // CCW covers only half the circle: H is evaluated where both runs have data.
  const auto cw = ovalPath(Point2::Zero(), 50.0, 0.0, 0.0, 72, true);
  std::vector<Point2> half;
  for (int k = 0; k <= 36; ++k) {
    const double t = std::numbers::pi * k / 36.0;
    half.emplace_back((50.0 + 0.001) * Point2(std::cos(t), std::sin(t)));
  }
  const auto [h, theta] = circularHysteresis(cw, half, Point2::Zero());
  EXPECT_NEAR(h, 0.001, kTolCircular);
  EXPECT_GE(theta, 0.0);
}

TEST(CircularTest, RejectsBadInput) {
  const auto ok = ovalPath(Point2::Zero(), 50.0, 0.0, 0.0, 12, true);
  const std::vector<Point2> few(ok.begin(), ok.begin() + 3);
  EXPECT_THROW((void)evaluateCircularTest(few, ok), InvalidArgument);
  CircularTestOptions nominal;
  nominal.centre = CircularCentre::kNominal;
  EXPECT_THROW((void)evaluateCircularTest(ok, ok, nominal), InvalidArgument);
  CircularTestOptions negative;
  negative.nominal_radius = -1.0;
  EXPECT_THROW((void)evaluateCircularTest(ok, ok, negative), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::metrology
