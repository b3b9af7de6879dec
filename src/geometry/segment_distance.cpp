#include "pkm/geometry/segment_distance.hpp"

#include <algorithm>

namespace pkm::geometry {

namespace {
double clamp01(double x) { return std::clamp(x, 0.0, 1.0); }
}  // namespace

SegmentDistance segmentDistance(const Eigen::Vector3d& p0,
                                const Eigen::Vector3d& p1,
                                const Eigen::Vector3d& q0,
                                const Eigen::Vector3d& q1) {
  // Minimise |p0 + s·d1 - q0 - t·d2|^2 over the unit square: the interior stationary point if it
  // exists, otherwise the best of the edges (each edge is a clamped 1-D projection).
  const Eigen::Vector3d d1 = p1 - p0;
  const Eigen::Vector3d d2 = q1 - q0;
  const Eigen::Vector3d r = p0 - q0;
  const double a = d1.squaredNorm();
  const double e = d2.squaredNorm();
  const double b = d1.dot(d2);
  const double c = d1.dot(r);
  const double f = d2.dot(r);
  const double scale = std::max({a, e, 1e-300});
  constexpr double kDegenerate = 1e-24;

  auto evaluate = [&](double s, double t) {
    SegmentDistance out;
    out.s = s;
    out.t = t;
    out.p = p0 + s * d1;
    out.q = q0 + t * d2;
    out.distance = (out.p - out.q).norm();
    return out;
  };

  if (a <= kDegenerate * scale && e <= kDegenerate * scale) return evaluate(0.0, 0.0);
  if (a <= kDegenerate * scale) return evaluate(0.0, clamp01(f / e));
  if (e <= kDegenerate * scale) return evaluate(clamp01(-c / a), 0.0);

  const double denom = a * e - b * b;
  if (denom > 1e-14 * a * e) {
    const double s = (b * f - c * e) / denom;
    const double t = (a * f - b * c) / denom;
    if (s >= 0.0 && s <= 1.0 && t >= 0.0 && t <= 1.0) return evaluate(s, t);
  }
  // Boundary: fix one parameter at 0 or 1 and clamp the optimal other one.
  SegmentDistance best = evaluate(0.0, clamp01(f / e));
  auto consider = [&best](const SegmentDistance& cand) {
    if (cand.distance < best.distance) best = cand;
  };
  consider(evaluate(1.0, clamp01((f + b) / e)));
  consider(evaluate(clamp01(-c / a), 0.0));
  consider(evaluate(clamp01((b - c) / a), 1.0));
  return best;
}

}  // namespace pkm::geometry
