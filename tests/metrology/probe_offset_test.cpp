#include "pkm/metrology/probe_offset.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/metrology/min_zone_circle.hpp"
#include "support/tolerances.hpp"

namespace pkm::metrology {
namespace PKM_TEST_NS {

using test::kSeed;
constexpr double kTolProbe = 1e-10;     ///< exact data: offset, centre, radii, mm
constexpr double kRing = 40.001 / 2.0;  ///< seed 003 Table 2: master ring, radius mm
constexpr double kBall = 3.0;           ///< stylus-ball radius, mm (RMP600 with a 6 mm ball)

Eigen::Matrix2d rot(double a) {
  Eigen::Matrix2d r;
  r << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  return r;
}

/// The spindle position at which a tool turned by ψ touches the ring moving from `start` along
/// `dir` (exact geometry: the ball centre reaches the circle of radius R − r about c).
Point2 touch(
    const Point2& c, const Eigen::Vector2d& d, double psi, const Point2& start, const Point2& dir) {
  const Point2 b0 = start + rot(psi) * d - c;  // ball centre relative to c at the start
  const double rho = kRing - kBall;
  const double bd = b0.dot(dir);
  const double t = -bd + std::sqrt(bd * bd - (b0.squaredNorm() - rho * rho));
  return start + t * dir;
}

TEST(ProbeOffset, Eq9ArithmeticOfThePaper) {
  // Seed 003 Table 3 (ring at {-0.625, 200.914}): o_probe = 0.210, 0.160 mm. The paper prints no
  // touch coordinates; eq. 9 applied to touches with x2 − x1 = ρ − 2·0.210 and y3 − y1 =
  // ρ − 2·0.160 returns them (the arithmetic of eq. 9 as printed).
  const double rho = kRing - kBall;
  const double x1 = -0.625, y1 = 200.914;
  const Eigen::Vector2d o =
      probeOffsetEq9(x1, y1, x1 + rho - 0.420, y1 + rho - 0.320, kRing, kBall);
  EXPECT_NEAR(o.x(), 0.210, test::kTolExact);
  EXPECT_NEAR(o.y(), 0.160, test::kTolExact);
}

TEST(ProbeOffset, Eq8IsExactAndEq9HasTheSmallAngleError) {
  // Physical stylus offset d = −o_probe; centre the ball at spindle 0°, reverse, touch +X and +Y.
  const Point2 c(-0.625, 200.914);
  const Eigen::Vector2d o(0.210, 0.160);
  const Eigen::Vector2d d = -o;
  const Point2 p1 = c - d;  // ball centred at ψ = 0
  const Point2 p2 = touch(c, d, std::numbers::pi, p1, Point2(1.0, 0.0));
  const Point2 p3 = touch(c, d, std::numbers::pi, p1, Point2(0.0, 1.0));
  const Eigen::Vector2d exact = probeOffsetEq8(p1.x(), p1.y(), p2.x(), p3.y(), kRing, kBall);
  EXPECT_NEAR(exact.x(), o.x(), kTolProbe);
  EXPECT_NEAR(exact.y(), o.y(), kTolProbe);
  // Eq. 9 drops ρ(1 − cos θ2)/2 with sin θ2 = 2 o_y/ρ (and likewise for y).
  const double rho = kRing - kBall;
  const Eigen::Vector2d approx = probeOffsetEq9(p1.x(), p1.y(), p2.x(), p3.y(), kRing, kBall);
  const double sx = 2.0 * o.y() / rho;
  const double sy = 2.0 * o.x() / rho;
  EXPECT_NEAR(approx.x() - o.x(), rho * (1.0 - std::sqrt(1.0 - sx * sx)) / 2.0, kTolProbe);
  EXPECT_NEAR(approx.y() - o.y(), rho * (1.0 - std::sqrt(1.0 - sy * sy)) / 2.0, kTolProbe);
}

TEST(ProbeOffset, LeastSquaresRecoversOffsetCentreAndStylusRadius) {
  // Touches at spindle 0° and 180° around the ring, each tool turn perturbed by a DRM-like angle.
  const Point2 c(-316.081, 247.037);
  const Eigen::Vector2d d(-0.210, -0.160);
  std::vector<ProbeTouch> touches;
  for (int k = 0; k < 24; ++k) {
    const double theta = 2.0 * std::numbers::pi * k / 12.0;
    const double psi = (k < 12 ? 0.0 : std::numbers::pi) + 0.03 * std::sin(theta);
    const Point2 dir(std::cos(theta), std::sin(theta));
    touches.push_back({psi, touch(c, d, psi, c - rot(psi) * d, dir)});
  }
  const ProbeOffsetFit fit = fitProbeOffset(touches);
  EXPECT_NEAR(fit.offset.x(), d.x(), kTolProbe);
  EXPECT_NEAR(fit.offset.y(), d.y(), kTolProbe);
  EXPECT_NEAR((fit.ring_center - c).norm(), 0.0, kTolProbe);
  EXPECT_NEAR(effectiveStylusRadius(2.0 * kRing, fit.ball_path_radius), kBall, kTolProbe);
  EXPECT_LT(fit.rms, kTolProbe);

  // With noise of an RMP600 (0.25 µm 2σ, datasheet) the offset is within a few σ/√N.
  std::mt19937 rng(kSeed);
  const double sigma = 0.125e-3;
  std::normal_distribution<double> noise(0.0, sigma);
  auto noisy = touches;
  for (ProbeTouch& t : noisy) t.position += Point2(noise(rng), noise(rng));
  const ProbeOffsetFit nf = fitProbeOffset(noisy);
  EXPECT_NEAR((nf.offset - d).norm(), 0.0, 5.0 * sigma);

  // The surface points corrected with the true turn lie on the ring; uncorrected (ψ = 0 for the
  // 0° touches, i.e. the DRM ignored) they do not.
  std::vector<ProbeTouch> first(touches.begin(), touches.begin() + 12);
  const auto good = correctedSurfacePoints(first, d, kBall, c);
  EXPECT_LT(fitCircle(good).roundness, kTolProbe);
  EXPECT_NEAR(fitCircle(good).circle.radius, kRing, kTolProbe);
  auto ignored = first;
  for (ProbeTouch& t : ignored) t.angle = 0.0;
  EXPECT_GT(fitMinimumZoneCircle(correctedSurfacePoints(ignored, d, kBall, c)).roundness, 1e-3);
}

TEST(ProbeOffset, RejectsUnseparableTouches) {
  std::vector<ProbeTouch> one_angle;
  for (int k = 0; k < 8; ++k) {
    const double t = 2.0 * std::numbers::pi * k / 8.0;
    one_angle.push_back({0.0, 17.0 * Point2(std::cos(t), std::sin(t))});
  }
  EXPECT_THROW((void)fitProbeOffset(one_angle), InvalidArgument);
  EXPECT_THROW((void)fitProbeOffset(std::span(one_angle).first(4)), InvalidArgument);
  EXPECT_THROW((void)probeOffsetEq9(0.0, 0.0, 1.0, 1.0, 2.0, 3.0), InvalidArgument);
  EXPECT_THROW((void)effectiveStylusRadius(-1.0, 1.0), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::metrology

namespace pkm::metrology {
namespace PKM_TEST_NS {

// Convergence on noisy touches: a probe repeats to about 1 µm, and a criterion below the rounding
// floor of the fit's sums would run every fit to its iteration limit.
constexpr double kProbeNoise = 0.001;   ///< mm, touch noise per axis (1 µm)
constexpr int kMaxProbeIterations = 6;  ///< Gauss-Newton steps on noisy touches
constexpr double kTolGradient = 1e-12;  ///< |Jᵀe| / N at the fit: the shift it implies, mm
constexpr double kTolStrictRerun =
    1e-9;  ///< centre, offset, radius: default vs strict criteria, mm

/// Noisy touches of seed 003's ring and stylus: `per_angle` touches around the ring at each
/// spindle angle in `angles`, each turn perturbed by a DRM-like 0.03·sin θ rad.
std::vector<ProbeTouch> noisyTouches(const Point2& c,
                                     const Eigen::Vector2d& d,
                                     const std::vector<double>& angles,
                                     int per_angle,
                                     unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, kProbeNoise);
  std::vector<ProbeTouch> touches;
  for (const double spindle : angles) {
    for (int k = 0; k < per_angle; ++k) {
      const double theta = 2.0 * std::numbers::pi * (k + 0.25) / per_angle;
      const double psi = spindle + 0.03 * std::sin(theta);
      const Point2 dir(std::cos(theta), std::sin(theta));
      Point2 s = touch(c, d, psi, c - rot(psi) * d, dir);
      s += Point2(noise(rng), noise(rng));
      touches.push_back({psi, s});
    }
  }
  return touches;
}

/// Gradient of ½Σe² over (centre, offset, radius) at the fit, divided by the number of touches.
double gradientPerTouch(std::span<const ProbeTouch> touches, const ProbeOffsetFit& fit) {
  Eigen::Matrix<double, 5, 1> g = Eigen::Matrix<double, 5, 1>::Zero();
  for (const ProbeTouch& t : touches) {
    const Point2 v = ballCentre(t, fit.offset) - fit.ring_center;
    const Point2 n = v.normalized();
    Eigen::Matrix<double, 5, 1> j;
    j << -n, rot(t.angle).transpose() * n, -1.0;
    g += j * (v.norm() - fit.ball_path_radius);
  }
  return g.norm() / static_cast<double>(touches.size());
}

TEST(ProbeOffset, ConvergesInAFewIterationsOnNoisyTouches) {
  const Point2 c(-316.081, 247.037);
  const Eigen::Vector2d d(-0.210, -0.160);
  // Seed 003's reversal (0° and 180°), and a three-angle set.
  const std::vector<std::vector<double>> sets{{0.0, std::numbers::pi},
                                              {0.0, std::numbers::pi / 2.0, std::numbers::pi}};
  for (const auto& angles : sets) {
    SCOPED_TRACE(angles.size());
    const auto touches = noisyTouches(c, d, angles, 20, kSeed + 1);
    const ProbeOffsetFit fit = fitProbeOffset(touches);
    EXPECT_TRUE(fit.converged);
    EXPECT_LE(fit.iterations, kMaxProbeIterations);
    RecordProperty("iterations_" + std::to_string(angles.size()) + "_angles", fit.iterations);
    EXPECT_LT(gradientPerTouch(touches, fit), kTolGradient);
    // The noise-limited truth: a few σ/√(touches per angle).
    const double tol = 5.0 * kProbeNoise;
    EXPECT_NEAR((fit.offset - d).norm(), 0.0, tol);
    EXPECT_NEAR((fit.ring_center - c).norm(), 0.0, tol);
    EXPECT_NEAR(effectiveStylusRadius(2.0 * kRing, fit.ball_path_radius), kBall, tol);
    EXPECT_NEAR(fit.rms, kProbeNoise, 0.5 * kProbeNoise);
    // Stricter criteria do not move the answer: it is the minimum, not an early stop.
    ProbeOffsetOptions strict;
    strict.step_tolerance = 1e-15;
    strict.cost_tolerance = 1e-15;
    const ProbeOffsetFit tight = fitProbeOffset(touches, strict);
    EXPECT_NEAR((tight.offset - fit.offset).norm(), 0.0, kTolStrictRerun);
    EXPECT_NEAR((tight.ring_center - fit.ring_center).norm(), 0.0, kTolStrictRerun);
    EXPECT_NEAR(tight.ball_path_radius, fit.ball_path_radius, kTolStrictRerun);
  }
}

TEST(ProbeOffset, ConvergesWhenOnlyTheDrmTurnsTheTool) {
  // No reversal: the tool turns only by the DRM (±0.03 rad), so centre and offset are separated
  // weakly (condition ~1/0.03²) and the step's rounding is far above the old 1e-14·ρ criterion.
  const Point2 c(-316.081, 247.037);
  const Eigen::Vector2d d(-0.210, -0.160);
  const auto touches = noisyTouches(c, d, {0.0}, 60, kSeed + 2);
  const ProbeOffsetFit fit = fitProbeOffset(touches);
  EXPECT_TRUE(fit.converged);
  EXPECT_LE(fit.iterations, kMaxProbeIterations);
  RecordProperty("iterations", fit.iterations);
  EXPECT_LT(gradientPerTouch(touches, fit), kTolGradient);
  ProbeOffsetOptions strict;
  strict.step_tolerance = 1e-15;
  strict.cost_tolerance = 1e-15;
  const ProbeOffsetFit tight = fitProbeOffset(touches, strict);
  EXPECT_NEAR((tight.offset - fit.offset).norm(), 0.0, kTolStrictRerun);
  // σ/0.03 per touch: the offset is known to tens of µm only.
  EXPECT_NEAR((fit.offset - d).norm(), 0.0, 5.0 * kProbeNoise / 0.03 / std::sqrt(60.0 / 2.0));
}

TEST(ProbeOffset, Eq8ConvergesToItsRoundingFloorInAFewSteps) {
  constexpr int kMaxEq8Iterations = 8;
  const Point2 c(-0.625, 200.914);
  std::mt19937 rng(kSeed + 3);
  std::normal_distribution<double> noise(0.0, kProbeNoise);
  for (const Eigen::Vector2d& o : {Eigen::Vector2d(0.210, 0.160), Eigen::Vector2d(-1.5, 2.0)}) {
    const Eigen::Vector2d d = -o;
    const Point2 p1 = c - d + Point2(noise(rng), noise(rng));
    const Point2 p2 = touch(c, d, std::numbers::pi, p1, Point2(1.0, 0.0));
    const Point2 p3 = touch(c, d, std::numbers::pi, p1, Point2(0.0, 1.0));
    const double x2 = p2.x() + noise(rng), y3 = p3.y() + noise(rng);
    const ProbeOffsetEq8Solution s = solveProbeOffsetEq8(p1.x(), p1.y(), x2, y3, kRing, kBall);
    EXPECT_TRUE(s.converged);
    EXPECT_LE(s.iterations, kMaxEq8Iterations);
    RecordProperty("iterations_offset_" + std::to_string(o.norm()), s.iterations);
    // A fixed point of eq. 8 (its residual), within the noise of the touches.
    const double rho = kRing - kBall;
    const double sin2 = 2.0 * s.o_probe.y() / rho, cos3 = 2.0 * s.o_probe.x() / rho;
    EXPECT_NEAR(x2 - p1.x(), rho * std::sqrt(1 - sin2 * sin2) - 2.0 * s.o_probe.x(), 1e-12);
    EXPECT_NEAR(y3 - p1.y(), rho * std::sqrt(1 - cos3 * cos3) - 2.0 * s.o_probe.y(), 1e-12);
    EXPECT_NEAR((s.o_probe - o).norm(), 0.0, 5.0 * kProbeNoise);
    EXPECT_EQ(probeOffsetEq8(p1.x(), p1.y(), x2, y3, kRing, kBall), s.o_probe);
  }
}

TEST(ProbeOffset, InvalidOptionsAreRejected) {
  const auto touches = noisyTouches(Point2(0, 0), Eigen::Vector2d(0.1, 0.0), {0.0, 3.0}, 4, kSeed);
  ProbeOffsetOptions o;
  o.cost_tolerance = 0.0;
  EXPECT_THROW((void)fitProbeOffset(touches, o), InvalidArgument);
  o = {};
  o.max_iterations = 0;
  std::string why;
  EXPECT_FALSE(o.isValid(&why));
  EXPECT_NE(why.find("max_iterations"), std::string::npos);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::metrology
