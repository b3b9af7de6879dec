#include "pkm/metrology/probe_offset.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "pkm/core/error.hpp"
#include "pkm/metrology/checks.hpp"

namespace pkm::metrology {
namespace {

Eigen::Matrix2d rot(double a) {
  const double c = std::cos(a);
  const double s = std::sin(a);
  Eigen::Matrix2d r;
  r << c, -s, s, c;
  return r;
}

double checkedPathRadius(std::initializer_list<double> values, double ring, double stylus) {
  for (double v : values) PKM_CHECK(std::isfinite(v), "probe offset: non-finite input");
  PKM_CHECK(ring > 0.0 && stylus >= 0.0 && stylus < ring,
            "probe offset: need 0 <= stylus radius < ring radius");
  return ring - stylus;
}

/// The touches' positions; rejects non-finite touches and touches all at one spindle angle.
std::vector<Point2> checkedTouchPositions(std::span<const ProbeTouch> touches) {
  std::vector<Point2> s(touches.size());
  double amin = touches[0].angle;
  double amax = amin;
  for (std::size_t k = 0; k < touches.size(); ++k) {
    PKM_CHECK(std::isfinite(touches[k].angle) && std::isfinite(touches[k].position.x()) &&
                  std::isfinite(touches[k].position.y()),
              "probe offset: touch {} of {} is not finite",
              k + 1,
              touches.size());
    s[k] = touches[k].position;
    amin = std::min(amin, touches[k].angle);
    amax = std::max(amax, touches[k].angle);
  }
  constexpr double kMinAngleSpread = 1e-3;  // rad: c and d are confounded at one angle
  PKM_CHECK(amax - amin > kMinAngleSpread,
            "probe offset: all touches have the same spindle angle (offset and centre are not "
            "separable)");
  return s;
}

/// Fills `fit` from the parameters p = (cx, cy, dx, dy, ρ) (centre relative to `origin`, mm):
/// ring centre, offset, ball path radius, and the residuals of `touches` with their RMS.
void setProbeOffsetResult(std::span<const ProbeTouch> touches,
                          const Point2& origin,
                          const Eigen::Matrix<double, 5, 1>& p,
                          ProbeOffsetFit& fit) {
  fit.ring_center = origin + p.head<2>();
  fit.offset = p.segment<2>(2);
  fit.ball_path_radius = p(4);
  fit.residuals.resize(touches.size());
  double sq = 0.0;
  for (std::size_t k = 0; k < touches.size(); ++k) {
    const double e = (ballCentre(touches[k], fit.offset) - fit.ring_center).norm() - p(4);
    fit.residuals[k] = e;
    sq += e * e;
  }
  fit.rms = std::sqrt(sq / static_cast<double>(touches.size()));
}

}  // namespace

Eigen::Vector2d probeOffsetEq9(
    double x1, double y1, double x2, double y3, double ring_radius, double stylus_radius) {
  const double rho =
      checkedPathRadius({x1, y1, x2, y3, ring_radius, stylus_radius}, ring_radius, stylus_radius);
  /// Lee et al. (2019), eq. 9.
  return {(-x2 + x1 + rho) / 2.0, (-y3 + y1 + rho) / 2.0};
}

ProbeOffsetEq8Solution solveProbeOffsetEq8(
    double x1, double y1, double x2, double y3, double ring_radius, double stylus_radius) {
  const double rho =
      checkedPathRadius({x1, y1, x2, y3, ring_radius, stylus_radius}, ring_radius, stylus_radius);
  ProbeOffsetEq8Solution out;
  Eigen::Vector2d& o = out.o_probe;
  o = probeOffsetEq9(x1, y1, x2, y3, ring_radius, stylus_radius);
  constexpr int kMaxIterations = 100;
  // Newton on F(o) = 0, F = (ρ cos θ2 − (x2 − x1) − 2 o_x, ρ sin θ3 − (y3 − y1) − 2 o_y): the
  // plain fixed-point map contracts only by about 2|o|/ρ per step (20 steps for a 2 mm offset in
  // a 17 mm path), Newton reaches the rounding floor of the ρ-sized terms, ε·ρ, in a few steps.
  constexpr double kStepUlps = 8.0;
  const double floor = kStepUlps * std::numeric_limits<double>::epsilon() * rho;
  for (int it = 0; it < kMaxIterations; ++it) {
    const double sin2 = 2.0 * o.y() / rho;  // +X touch: the ball keeps y, eq. 8 geometry
    const double cos3 = 2.0 * o.x() / rho;  // +Y touch: the ball keeps x
    PKM_CHECK(std::abs(sin2) < 1.0 && std::abs(cos3) < 1.0,
              "probe offset: the offset does not fit inside the ring");
    const double cos2 = std::sqrt(1.0 - sin2 * sin2);
    const double sin3 = std::sqrt(1.0 - cos3 * cos3);
    /// Lee et al. (2019), eq. 8: x2 − x1 = ρ cos θ2 − 2 o_x, y3 − y1 = ρ sin θ3 − 2 o_y.
    const Eigen::Vector2d f(rho * cos2 - (x2 - x1) - 2.0 * o.x(),
                            rho * sin3 - (y3 - y1) - 2.0 * o.y());
    Eigen::Matrix2d j;
    j << -2.0, -2.0 * sin2 / cos2, -2.0 * cos3 / sin3, -2.0;
    const Eigen::Vector2d step = -j.partialPivLu().solve(f);
    PKM_CHECK(step.allFinite(), "probe offset: the offset does not fit inside the ring");
    o += step;
    out.iterations = it + 1;
    if (step.norm() <= floor) {
      out.converged = true;
      break;
    }
  }
  return out;
}

Eigen::Vector2d probeOffsetEq8(
    double x1, double y1, double x2, double y3, double ring_radius, double stylus_radius) {
  const ProbeOffsetEq8Solution s = solveProbeOffsetEq8(x1, y1, x2, y3, ring_radius, stylus_radius);
  PKM_CHECK(s.converged,
            "probe offset: eq. 8 did not converge in {} iterations (offset too large for the "
            "ring?)",
            s.iterations);
  return s.o_probe;
}

Point2 ballCentre(const ProbeTouch& touch, const Eigen::Vector2d& offset) {
  return touch.position + rot(touch.angle) * offset;
}

bool ProbeOffsetOptions::isValid(std::string* why) const {
  const char* reason =
      levenbergMarquardtSettingsProblem(max_iterations, step_tolerance, cost_tolerance);
  if (reason != nullptr && why != nullptr) *why = reason;
  return reason == nullptr;
}

ProbeOffsetFit fitProbeOffset(std::span<const ProbeTouch> touches,
                              const ProbeOffsetOptions& options) {
  std::string why;
  PKM_CHECK(options.isValid(&why), "probe offset: {}", why);
  requireCount(touches.size(), 5, "probe offset");
  const std::vector<Point2> s = checkedTouchPositions(touches);
  const CircleFit start = fitCircle(s);
  const Point2 origin = start.circle.center;
  // Parameters (cx, cy, dx, dy, ρ), centre relative to `origin`.
  Eigen::Matrix<double, 5, 1> p;
  p << 0.0, 0.0, 0.0, 0.0, start.circle.radius;
  ProbeOffsetFit fit;
  // A sum of N squares carries a relative rounding error up to N·ε: a cost change below that
  // cannot be told from none (as in fitCircle), so the step before it reached the minimum.
  const double floor = static_cast<double>(touches.size()) * std::numeric_limits<double>::epsilon();
  double previous_cost = std::numeric_limits<double>::infinity();
  for (int it = 0; it < options.max_iterations; ++it) {
    Eigen::Matrix<double, 5, 5> jtj = Eigen::Matrix<double, 5, 5>::Zero();
    Eigen::Matrix<double, 5, 1> jte = Eigen::Matrix<double, 5, 1>::Zero();
    double cost = 0.0;
    for (const ProbeTouch& t : touches) {
      const Eigen::Matrix2d r = rot(t.angle);
      const Point2 v = t.position - origin + r * p.segment<2>(2) - p.head<2>();
      const double d = v.norm();
      PKM_CHECK(d > 0.0, "probe offset: a ball centre coincides with the ring centre");
      const Point2 n = v / d;
      Eigen::Matrix<double, 5, 1> j;
      j << -n, r.transpose() * n, -1.0;
      jtj.noalias() += j * j.transpose();
      jte += j * (d - p(4));
      cost += (d - p(4)) * (d - p(4));
    }
    // The last step changed the cost by a negligible fraction: p is the minimum.
    if (std::abs(previous_cost - cost) <= std::max(options.cost_tolerance, floor) * cost) {
      fit.converged = true;
      break;
    }
    previous_cost = cost;
    // Dynamic size: GCC 12 warns falsely (maybe-uninitialized) on the fixed-size 5x5 SVD.
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Eigen::MatrixXd(jtj),
                                                Eigen::ComputeThinU | Eigen::ComputeThinV);
    constexpr double kMinConditionReciprocal = 1e-12;
    PKM_CHECK(svd.singularValues()(4) > kMinConditionReciprocal * svd.singularValues()(0),
              "probe offset: singular problem (touches do not separate ring centre and offset; "
              "touch around the ring at two or more spindle angles)");
    const Eigen::Matrix<double, 5, 1> step = svd.solve(Eigen::VectorXd(-jte));
    p += step;
    fit.iterations = it + 1;
    if (step.norm() <= options.step_tolerance * std::max(1.0, p(4))) {
      fit.converged = true;
      break;
    }
  }
  setProbeOffsetResult(touches, origin, p, fit);
  return fit;
}

double effectiveStylusRadius(double ring_diameter, double ball_path_radius) {
  PKM_CHECK(ring_diameter > 0.0 && std::isfinite(ring_diameter),
            "effective stylus radius: the ring diameter must be > 0");
  return ring_diameter / 2.0 - ball_path_radius;
}

std::vector<Point2> correctedSurfacePoints(std::span<const ProbeTouch> touches,
                                           const Eigen::Vector2d& offset,
                                           double stylus_radius,
                                           const Point2& nominal_center) {
  PKM_CHECK(stylus_radius >= 0.0 && std::isfinite(stylus_radius),
            "corrected surface points: the stylus radius must be >= 0");
  std::vector<Point2> out;
  out.reserve(touches.size());
  for (const ProbeTouch& t : touches) {
    const Point2 b = ballCentre(t, offset);
    const Point2 v = b - nominal_center;
    PKM_CHECK(v.norm() > 0.0, "corrected surface points: a touch at the nominal centre");
    out.push_back(b + stylus_radius * v.normalized());
  }
  return out;
}

}  // namespace pkm::metrology
