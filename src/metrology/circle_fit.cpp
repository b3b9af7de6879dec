#include "pkm/metrology/circle_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "pkm/core/error.hpp"
#include "pkm/metrology/checks.hpp"

namespace pkm::metrology {
namespace {

/// Centroid and RMS distance from it: the shift and scale under which the fits are conditioned
/// (large coordinates are known to make circle regressions unstable).
struct Frame {
  Point2 origin = Point2::Zero();
  double scale = 1.0;
};

Frame conditioningFrame(std::span<const Point2> points) {
  Point2 sum = Point2::Zero();
  for (const Point2& p : points) sum += p;
  Frame frame;
  frame.origin = sum / static_cast<double>(points.size());
  double sq = 0.0;
  for (const Point2& p : points) sq += (p - frame.origin).squaredNorm();
  frame.scale = std::sqrt(sq / static_cast<double>(points.size()));
  PKM_CHECK(frame.scale > 0.0 && std::isfinite(frame.scale), "circle fit: the points all coincide");
  return frame;
}

/// Kåsa on the conditioned points: returns centre and radius in conditioned units.
Circle kasaConditioned(std::span<const Point2> points, const Frame& frame) {
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
  for (const Point2& p : points) {
    const Point2 u = (p - frame.origin) / frame.scale;
    const Eigen::Vector3d row(u.x(), u.y(), 1.0);
    const double z = u.squaredNorm();
    normal.noalias() += row * row.transpose();
    rhs += row * z;
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(normal, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d sv = svd.singularValues();
  constexpr double kMinConditionReciprocal = 1e-13;  // collinear points make [u v 1] rank 2
  PKM_CHECK(sv(2) > kMinConditionReciprocal * sv(0),
            "circle fit: the points are collinear (no circle through them)");
  const Eigen::Vector3d abc = svd.solve(rhs);
  Circle c;
  c.center = Point2(abc(0) / 2.0, abc(1) / 2.0);
  c.radius = std::sqrt(std::max(abc(2) + c.center.squaredNorm(), 0.0));
  PKM_CHECK(c.radius > 0.0 && std::isfinite(c.radius), "circle fit: degenerate points");
  return c;
}

/// One pass: cost Σe², JᵀJ and Jᵀe of e_k = |u_k − c| − R for params (cx, cy, R).
struct Linearisation {
  double cost = 0.0;
  Eigen::Matrix3d jtj = Eigen::Matrix3d::Zero();
  Eigen::Vector3d jte = Eigen::Vector3d::Zero();
};

Linearisation linearise(std::span<const Point2> points,
                        const Frame& frame,
                        const Eigen::Vector3d& params) {
  Linearisation lin;
  for (const Point2& p : points) {
    const Point2 u = (p - frame.origin) / frame.scale;
    const double dx = u.x() - params(0);
    const double dy = u.y() - params(1);
    const double d = std::sqrt(dx * dx + dy * dy);
    const double e = d - params(2);
    Eigen::Vector3d j(0.0, 0.0, -1.0);
    if (d > 0.0) {
      j(0) = -dx / d;
      j(1) = -dy / d;
    }
    lin.cost += e * e;
    lin.jtj.noalias() += j * j.transpose();
    lin.jte += j * e;
  }
  return lin;
}

}  // namespace

void requirePoints(std::span<const Point2> points, std::size_t minimum, const char* what) {
  requireCount(points.size(), minimum, what);
  for (std::size_t i = 0; i < points.size(); ++i) {
    PKM_CHECK(std::isfinite(points[i].x()) && std::isfinite(points[i].y()),
              "{}: point {} of {} is not finite",
              what,
              i + 1,
              points.size());
  }
}

Circle fitCircleKasa(std::span<const Point2> points) {
  requirePoints(points, 3, "circle fit");
  const Frame frame = conditioningFrame(points);
  Circle c = kasaConditioned(points, frame);
  c.center = frame.origin + frame.scale * c.center;
  c.radius *= frame.scale;
  return c;
}

CircleFit fitCircle(std::span<const Point2> points, const CircleFitOptions& options) {
  PKM_CHECK(options.max_iterations >= 1, "circle fit: max_iterations must be >= 1");
  PKM_CHECK(options.step_tolerance > 0.0, "circle fit: step_tolerance must be > 0");
  requirePoints(points, 3, "circle fit");
  const Frame frame = conditioningFrame(points);
  const Circle start = kasaConditioned(points, frame);
  Eigen::Vector3d params(start.center.x(), start.center.y(), start.radius);

  // Levenberg-Marquardt (Marquardt's diagonal scaling) on the orthogonal distances.
  CircleFit fit;
  Linearisation lin = linearise(points, frame, params);
  double lambda = 1e-3;
  constexpr double kLambdaMax = 1e12;
  for (int it = 0; it < options.max_iterations; ++it) {
    fit.iterations = it + 1;
    Eigen::Matrix3d a = lin.jtj;
    a.diagonal() *= 1.0 + lambda;
    const Eigen::Vector3d step = a.ldlt().solve(-lin.jte);
    // A step shrunk by heavy damping is no sign of convergence: count it only for lambda <= 1.
    const bool small =
        lambda <= 1.0 && step.norm() <= options.step_tolerance * std::max(1.0, params(2));
    const Eigen::Vector3d trial = params + step;
    Linearisation next = linearise(points, frame, trial);
    if (next.cost <= lin.cost) {
      params = trial;
      lin = next;
      lambda = std::max(lambda * 0.1, 1e-12);
    } else {
      lambda *= 10.0;
    }
    if (small || lambda > kLambdaMax) {
      fit.converged = small;
      break;
    }
  }
  PKM_CHECK(params(2) > 0.0 && std::isfinite(params(2)), "circle fit: degenerate points");

  fit.circle.center = frame.origin + frame.scale * Point2(params(0), params(1));
  fit.circle.radius = frame.scale * std::abs(params(2));
  fit.residuals.resize(points.size());
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  double sq = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Point2 u = (points[k] - frame.origin) / frame.scale;
    const double e = frame.scale * ((u - Point2(params(0), params(1))).norm() - params(2));
    fit.residuals[k] = e;
    lo = std::min(lo, e);
    hi = std::max(hi, e);
    sq += e * e;
  }
  fit.roundness = hi - lo;
  fit.rms = std::sqrt(sq / static_cast<double>(points.size()));
  return fit;
}

std::vector<double> radialDistances(std::span<const Point2> points, const Point2& center) {
  std::vector<double> r(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) r[k] = (points[k] - center).norm();
  return r;
}

double roundnessAbout(std::span<const Point2> points, const Point2& center) {
  PKM_CHECK(!points.empty(), "roundness: no points");
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (const Point2& p : points) {
    const double r = (p - center).norm();
    lo = std::min(lo, r);
    hi = std::max(hi, r);
  }
  return hi - lo;
}

}  // namespace pkm::metrology
