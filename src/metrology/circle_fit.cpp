#include "pkm/metrology/circle_fit.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "pkm/core/error.hpp"
#include "pkm/core/parallel.hpp"
#include "pkm/metrology/checks.hpp"

namespace pkm::metrology {
namespace {

/// Σ_k f(p_k) for a function returning an N-vector: summed per chunk (pkm/core/parallel.hpp, on
/// the machine's cores), the chunks' sums added in order, so the result is the same everywhere.
template <int N, typename F>
Eigen::Matrix<double, N, 1> sumOver(std::span<const Point2> points, F&& f) {
  using Vec = Eigen::Matrix<double, N, 1>;
  std::array<Vec, kParallelChunks> part;
  forEachChunk(points.size(), kParallelChunks, [&](std::size_t c, std::size_t b, std::size_t e) {
    Vec sum = Vec::Zero();
    for (std::size_t k = b; k < e; ++k) sum += f(points[k]);
    part[c] = sum;
  });
  Vec total = Vec::Zero();
  for (const Vec& v : part) total += v;
  return total;
}

/// Centroid and RMS distance from it: the shift and scale under which the fits are conditioned
/// (large coordinates are known to make circle regressions unstable).
struct Frame {
  Point2 origin = Point2::Zero();
  double scale = 1.0;
};

Frame conditioningFrame(std::span<const Point2> points) {
  const auto n = static_cast<double>(points.size());
  // One pass: the sums of q and |q|² with q = p − p₀ (the first point: shifted sums keep the
  // centroid's and the spread's digits, which raw sums of large coordinates lose). A point that is
  // not finite makes them not finite; requirePoints then names it.
  const Point2 p0 = points.front();
  const Eigen::Vector3d s = sumOver<3>(points, [&](const Point2& p) {
    const Point2 q = p - p0;
    return Eigen::Vector3d(q.x(), q.y(), q.squaredNorm());
  });
  if (!s.allFinite()) requirePoints(points, 3, "circle fit");
  const Point2 mean = s.head<2>() / n;
  Frame frame;
  frame.origin = p0 + mean;
  // Σ|p − origin|² = Σ|q|² − n·|mean|², never below 0 in exact arithmetic.
  frame.scale = std::sqrt(std::max(s(2) / n - mean.squaredNorm(), 0.0));
  PKM_CHECK(frame.scale > 0.0 && std::isfinite(frame.scale), "circle fit: the points all coincide");
  return frame;
}

/// Kåsa on the conditioned points: returns centre and radius in conditioned units.
Circle kasaConditioned(std::span<const Point2> points, const Frame& frame) {
  const double inv_scale = 1.0 / frame.scale;
  // Σ of u², uv, v², u, v, z·u, z·v, z over u = conditioned point, z = |u|².
  const Eigen::Matrix<double, 8, 1> s = sumOver<8>(points, [&](const Point2& p) {
    const Point2 u = (p - frame.origin) * inv_scale;
    const double z = u.squaredNorm();
    Eigen::Matrix<double, 8, 1> t;
    t << u.x() * u.x(), u.x() * u.y(), u.y() * u.y(), u.x(), u.y(), z * u.x(), z * u.y(), z;
    return t;
  });
  Eigen::Matrix3d normal;
  normal << s(0), s(1), s(3), s(1), s(2), s(4), s(3), s(4), static_cast<double>(points.size());
  const Eigen::Vector3d rhs(s(5), s(6), s(7));
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

/// One pass: cost Σe², JᵀJ and Jᵀe of e_k = |u_k − c| − R for params (cx, cy, R), with the
/// Jacobian row (−cos φ_k, −sin φ_k, −1) accumulated as its distinct sums.
struct Linearisation {
  double cost = 0.0;
  Eigen::Matrix3d jtj = Eigen::Matrix3d::Zero();
  Eigen::Vector3d jte = Eigen::Vector3d::Zero();
};

Linearisation linearise(std::span<const Point2> points,
                        const Frame& frame,
                        const Eigen::Vector3d& params) {
  const double inv_scale = 1.0 / frame.scale;
  const double ox = frame.origin.x() + frame.scale * params(0);
  const double oy = frame.origin.y() + frame.scale * params(1);
  const double radius = params(2);
  // Σ of e², c², cs, s², c, s, ce, se, e with (c, s) the unit direction from the centre; two
  // points at a time (packed square roots and divisions, which bound this loop), in two lanes
  // added at the end of each chunk.
  using A2 = Eigen::Array2d;
  using Sums = std::array<double, 9>;
  std::array<Sums, kParallelChunks> part{};
  forEachChunk(
      points.size(), kParallelChunks, [&](std::size_t chunk, std::size_t b, std::size_t end) {
        std::array<A2, 9> acc;
        acc.fill(A2::Zero());
        const auto add = [&](const A2& dx, const A2& dy, const A2& mask) {
          const A2 d = (dx * dx + dy * dy).sqrt();
          const A2 e = (d - radius) * mask;
          const A2 inv_d = (d > 0.0).select(d.inverse(), 0.0) * mask;
          const A2 c = dx * inv_d;
          const A2 sn = dy * inv_d;
          acc[0] += e * e;
          acc[1] += c * c;
          acc[2] += c * sn;
          acc[3] += sn * sn;
          acc[4] += c;
          acc[5] += sn;
          acc[6] += c * e;
          acc[7] += sn * e;
          acc[8] += e;
        };
        std::size_t k = b;
        for (; k + 1 < end; k += 2) {
          const A2 dx((points[k].x() - ox) * inv_scale, (points[k + 1].x() - ox) * inv_scale);
          const A2 dy((points[k].y() - oy) * inv_scale, (points[k + 1].y() - oy) * inv_scale);
          add(dx, dy, A2::Ones());
        }
        if (k < end) {  // an odd point: the second lane adds nothing
          const A2 dx((points[k].x() - ox) * inv_scale, 0.0);
          const A2 dy((points[k].y() - oy) * inv_scale, 0.0);
          add(dx, dy, A2(1.0, 0.0));
        }
        for (std::size_t i = 0; i < 9; ++i) part[chunk][i] = acc[i].sum();
      });
  Sums t{};
  for (const Sums& p : part)
    for (std::size_t i = 0; i < 9; ++i) t[i] += p[i];
  Linearisation lin;
  lin.cost = t[0];
  lin.jtj << t[1], t[2], t[4], t[2], t[3], t[5], t[4], t[5], static_cast<double>(points.size());
  lin.jte << -t[6], -t[7], -t[8];
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

bool CircleFitOptions::isValid(std::string* why) const {
  const char* reason =
      levenbergMarquardtSettingsProblem(max_iterations, step_tolerance, cost_tolerance);
  if (reason != nullptr && why != nullptr) *why = reason;
  return reason == nullptr;
}

CircleFit fitCircle(std::span<const Point2> points, const CircleFitOptions& options) {
  std::string why;
  PKM_CHECK(options.isValid(&why), "circle fit: {}", why);
  requireCount(points.size(), 3, "circle fit");  // finiteness: conditioningFrame
  const Frame frame = conditioningFrame(points);
  const Circle start = kasaConditioned(points, frame);
  Eigen::Vector3d params(start.center.x(), start.center.y(), start.radius);

  // Levenberg-Marquardt (Marquardt's diagonal scaling) on the orthogonal distances. A sum of N
  // squares carries a relative rounding error up to N·ε: a trial whose cost differs from the
  // current one by less than that cannot be told apart from it, so the fit is at its minimum.
  const double floor = static_cast<double>(points.size()) * std::numeric_limits<double>::epsilon();
  CircleFit fit;
  Linearisation lin = linearise(points, frame, params);
  double lambda = 1e-3;
  constexpr double kLambdaMax = 1e12;
  for (int it = 0; it < options.max_iterations; ++it) {
    fit.iterations = it + 1;
    Eigen::Matrix3d a = lin.jtj;
    a.diagonal() *= 1.0 + lambda;
    const Eigen::Vector3d step = a.ldlt().solve(-lin.jte);
    if (!step.allFinite()) break;
    // A step shrunk by heavy damping is no sign of convergence: count it only for lambda <= 1.
    const bool small =
        lambda <= 1.0 && step.norm() <= options.step_tolerance * std::max(1.0, params(2));
    const Eigen::Vector3d trial = params + step;
    const Linearisation next = linearise(points, frame, trial);
    const double change = next.cost - lin.cost;
    if (change <= 0.0) {
      params = trial;
      lin = next;
      lambda = std::max(lambda * 0.1, 1e-12);
    } else {
      lambda *= 10.0;
    }
    const bool flat = change <= 0.0 && -change <= options.cost_tolerance * lin.cost;
    if (small || flat || std::abs(change) <= floor * lin.cost) {
      fit.converged = true;
      break;
    }
    if (lambda > kLambdaMax) break;
  }
  PKM_CHECK(params(2) > 0.0 && std::isfinite(params(2)), "circle fit: degenerate points");

  fit.circle.center = frame.origin + frame.scale * Point2(params(0), params(1));
  fit.circle.radius = frame.scale * std::abs(params(2));
  fit.residuals.resize(points.size());
  std::array<std::array<double, 3>, kParallelChunks> part{};  // min, max, Σe² per chunk
  forEachChunk(points.size(), kParallelChunks, [&](std::size_t c, std::size_t b, std::size_t end) {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    double sq = 0.0;
    for (std::size_t k = b; k < end; ++k) {
      const double e = (points[k] - fit.circle.center).norm() - fit.circle.radius;
      fit.residuals[k] = e;
      lo = std::min(lo, e);
      hi = std::max(hi, e);
      sq += e * e;
    }
    part[c] = {lo, hi, sq};
  });
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  double sq = 0.0;
  for (const auto& [l, h, q] : part) {
    lo = std::min(lo, l);
    hi = std::max(hi, h);
    sq += q;
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
