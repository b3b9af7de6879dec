#include "pkm/metrology/circle_fit.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace pkm::metrology {
namespace PKM_TEST_NS {

using test::kSeed;
constexpr double kTolFit = 1e-9;          ///< exact data: centre and radius, mm
constexpr double kTolStationary = 1e-10;  ///< normal equations of the geometric fit, mm
constexpr double kTolLinearised = 1e-6;   ///< ISO 4291 linearised LSC vs exact (second order), mm

std::vector<Point2> circlePoints(const Point2& c, double r, int n, double a0, double span) {
  std::vector<Point2> p;
  for (int k = 0; k < n; ++k) {
    const double t = a0 + span * k / n;
    p.emplace_back(c + r * Point2(std::cos(t), std::sin(t)));
  }
  return p;
}

TEST(CircleFit, RecoversAnExactCircleFarFromTheOrigin) {
  const Point2 c(12345.678, -9876.5);
  const auto pts = circlePoints(c, 20.0005, 36, 0.1, 2.0 * std::numbers::pi);
  const CircleFit fit = fitCircle(pts);
  EXPECT_TRUE(fit.converged);
  EXPECT_NEAR(fit.circle.center.x(), c.x(), kTolFit);
  EXPECT_NEAR(fit.circle.center.y(), c.y(), kTolFit);
  EXPECT_NEAR(fit.circle.radius, 20.0005, kTolFit);
  EXPECT_LT(fit.roundness, kTolFit);
  const Circle kasa = fitCircleKasa(pts);
  EXPECT_NEAR(kasa.radius, 20.0005, kTolFit);
}

/// The fit's own optimality: Σe_k and Σe_k·u_k (u_k the unit vector from the centre), mm.
double stationarity(const std::vector<Point2>& pts, const CircleFit& fit) {
  double se = 0.0;
  Point2 sn = Point2::Zero();
  for (std::size_t k = 0; k < pts.size(); ++k) {
    se += fit.residuals[k];
    sn += fit.residuals[k] * (pts[k] - fit.circle.center).normalized();
  }
  return std::max(std::abs(se), sn.norm());
}

TEST(CircleFit, ConvergesInAFewIterationsOnALargeNoisyCircle) {
  // A measured-like ring: 50 mm, 3- and 5-lobe form of 10 µm, 1 µm noise, 200 000 points (read
  // in parallel chunks). The old step criterion (1e-12 × R) was below the rounding floor of such
  // sums and ran all 100 iterations.
  constexpr int kMaxIterations = 6;
  constexpr double kTolNoisyStationary = 1e-9;  ///< (Σe, Σe·u) / N: the shift they imply, mm
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * std::numbers::pi);
  std::normal_distribution<double> noise(0.0, 0.001);
  std::vector<Point2> pts;
  for (int k = 0; k < 200000; ++k) {
    const double t = angle(rng);
    const double r = 50.0 + 0.005 * std::cos(3 * t + 0.4) + 0.002 * std::sin(5 * t) + noise(rng);
    pts.emplace_back(Point2(312.3, -4.56) + r * Point2(std::cos(t), std::sin(t)));
  }
  const CircleFit fit = fitCircle(pts);
  EXPECT_TRUE(fit.converged);
  EXPECT_LE(fit.iterations, kMaxIterations);
  EXPECT_LT(stationarity(pts, fit) / static_cast<double>(pts.size()), kTolNoisyStationary);
  EXPECT_NEAR(fit.circle.radius, 50.0, 1e-4);
  // Tighter criteria do not move the answer (it is the minimum, not an early stop).
  CircleFitOptions strict;
  strict.step_tolerance = 1e-15;
  strict.cost_tolerance = 1e-15;
  const CircleFit tight = fitCircle(pts, strict);
  EXPECT_NEAR(tight.circle.radius, fit.circle.radius, 1e-6 * fit.circle.radius);
  EXPECT_NEAR((tight.circle.center - fit.circle.center).norm(), 0.0, 1e-6 * fit.circle.radius);
}

TEST(CircleFit, ConvergesOnNoisyShortArcs) {
  constexpr int kMaxIterations = 20;
  std::mt19937 rng(kSeed);
  std::normal_distribution<double> noise(0.0, 0.002);
  for (const double span : {0.3, 1.0, 3.0}) {
    auto pts = circlePoints(Point2(-7.0, 40.0), 25.0, 400, 0.2, span);
    for (Point2& p : pts) p += Point2(noise(rng), noise(rng));
    const CircleFit fit = fitCircle(pts);
    EXPECT_TRUE(fit.converged) << span;
    EXPECT_LE(fit.iterations, kMaxIterations) << span;
    EXPECT_LT(stationarity(pts, fit), 1e-9) << span;
  }
}

TEST(CircleFit, InvalidOptionsAreRejected) {
  const auto pts = circlePoints(Point2(0, 0), 1.0, 8, 0.0, 6.0);
  CircleFitOptions o;
  o.cost_tolerance = 0.0;
  EXPECT_THROW((void)fitCircle(pts, o), InvalidArgument);
  EXPECT_FALSE(o.isValid());
  o = {};
  o.max_iterations = 0;
  std::string why;
  EXPECT_FALSE(o.isValid(&why));
  EXPECT_NE(why.find("max_iterations"), std::string::npos);
}

TEST(CircleFit, ShortArcBeatsKasaBias) {
  // Noisy 30° arc: Kåsa is biased; the geometric fit must be stationary (its own normal equations).
  std::mt19937 rng(kSeed);
  std::normal_distribution<double> noise(0.0, 0.01);
  auto pts = circlePoints(Point2(1.0, 2.0), 100.0, 50, 0.3, std::numbers::pi / 6.0);
  for (Point2& p : pts) p += Point2(noise(rng), noise(rng));
  const CircleFit fit = fitCircle(pts);
  EXPECT_TRUE(fit.converged);
  // Stationarity of Σ(|p − c| − R)²: Σ e_k = 0 and Σ e_k (p_k − c)/|p_k − c| = 0.
  double se = 0.0;
  Point2 sn = Point2::Zero();
  for (std::size_t k = 0; k < pts.size(); ++k) {
    se += fit.residuals[k];
    sn += fit.residuals[k] * (pts[k] - fit.circle.center).normalized();
  }
  EXPECT_NEAR(se, 0.0, kTolStationary);
  EXPECT_NEAR(sn.norm(), 0.0, kTolStationary);
  // Any perturbation of the solution raises the cost (a brute-force look around the minimum).
  const auto cost = [&](const Point2& c, double r) {
    double s = 0.0;
    for (const Point2& p : pts) s += std::pow((p - c).norm() - r, 2);
    return s;
  };
  const double best = cost(fit.circle.center, fit.circle.radius);
  for (double dx : {-1e-3, 1e-3})
    for (double dr : {-1e-3, 0.0, 1e-3}) {
      EXPECT_GT(cost(fit.circle.center + Point2(dx, 0.0), fit.circle.radius + dr), best);
      EXPECT_GT(cost(fit.circle.center + Point2(0.0, dx), fit.circle.radius + dr), best);
    }
  EXPECT_LT(cost(fit.circle.center, fit.circle.radius),
            cost(fitCircleKasa(pts).center, fitCircleKasa(pts).radius));
}

TEST(CircleFit, AgreesWithTheIso4291LinearisedFormula) {
  // Equally spaced angles about the origin, small eccentricity and a 3-lobe form: the explicit
  // ISO 4291 Annex F equations agree with the exact fit to second order.
  const int n = 72;
  const Point2 ecc(0.002, -0.001);
  std::vector<Point2> pts;
  std::vector<double> r(n);
  std::vector<double> th(n);
  for (int k = 0; k < n; ++k) {
    th[static_cast<std::size_t>(k)] = 2.0 * std::numbers::pi * k / n;
    const double t = th[static_cast<std::size_t>(k)];
    const Point2 u(std::cos(t), std::sin(t));
    // Limaçon of the eccentric circle, sampled at equal angles about the instrument centre.
    const double rad = 20.0 + ecc.dot(u) + 0.003 * std::cos(3.0 * t);
    pts.push_back(rad * u);
  }
  double a = 0.0, b = 0.0, rr = 0.0;
  for (int k = 0; k < n; ++k) {
    const std::size_t i = static_cast<std::size_t>(k);
    const double rk = pts[i].norm();
    const double t = std::atan2(pts[i].y(), pts[i].x());
    a += 2.0 / n * rk * std::cos(t);
    b += 2.0 / n * rk * std::sin(t);
    rr += rk / n;
  }
  const CircleFit fit = fitCircle(pts);
  EXPECT_NEAR(a, ecc.x(), kTolLinearised);
  EXPECT_NEAR(b, ecc.y(), kTolLinearised);
  EXPECT_NEAR(fit.circle.center.x(), a, kTolLinearised);
  EXPECT_NEAR(fit.circle.center.y(), b, kTolLinearised);
  EXPECT_NEAR(fit.circle.radius, rr, kTolLinearised);
  EXPECT_NEAR(fit.roundness, 0.006, kTolLinearised);  // the 3-lobe peak-to-valley
  EXPECT_NEAR(fit.roundness, roundnessAbout(pts, fit.circle.center), test::kTolExact);
}

TEST(CircleFit, RejectsBadInput) {
  const std::vector<Point2> two{{0.0, 0.0}, {1.0, 0.0}};
  EXPECT_THROW((void)fitCircle(two), InvalidArgument);
  const std::vector<Point2> line{{0.0, 0.0}, {1.0, 1.0}, {2.0, 2.0}, {3.0, 3.0}};
  EXPECT_THROW((void)fitCircle(line), InvalidArgument);
  const std::vector<Point2> same{{1.0, 1.0}, {1.0, 1.0}, {1.0, 1.0}};
  EXPECT_THROW((void)fitCircle(same), InvalidArgument);
  const std::vector<Point2> nan{
      {0.0, 0.0}, {1.0, 0.0}, {0.0, std::numeric_limits<double>::quiet_NaN()}};
  EXPECT_THROW((void)fitCircle(nan), InvalidArgument);
  EXPECT_THROW((void)roundnessAbout({}, Point2::Zero()), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::metrology
