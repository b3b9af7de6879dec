#include "pkm/cnc/cycle_time.hpp"

#include <algorithm>
#include <cmath>

#include "pkm/core/error.hpp"

namespace pkm::cnc {
namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
/// Speed reachable from `v` over `ds` with acceleration `a` (v² + 2·a·ds).
double reach(double v, double a, double ds) {
  if (ds <= 0.0) return v;
  if (!std::isfinite(a)) return kInf;
  return std::sqrt(v * v + 2.0 * a * ds);
}
}  // namespace

bool RapidAxisLimits::any() const {
  return std::isfinite(angular_rate) ||
         std::any_of(
             axis_velocity.begin(), axis_velocity.end(), [](double v) { return std::isfinite(v); });
}

void RapidAxisLimits::validate() const {
  for (std::size_t i = 0; i < axis_velocity.size(); ++i)
    PKM_CHECK(axis_velocity[i] > 0.0,
              "axis {} rapid velocity limit must be > 0 (got {})",
              "XYZABC"[i],
              axis_velocity[i]);
  PKM_CHECK(angular_rate > 0.0, "angular rapid rate must be > 0 (got {})", angular_rate);
}

double rapidSpeedCap(const Axes& a, const Axes& b, const RapidAxisLimits& limits) {
  const double l = segmentLength(a, b);
  if (!(l > 0.0)) return kInf;
  const bool rotary_only = !(std::hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]) > 0.0);
  double cap = rotary_only ? limits.angular_rate / 60.0 : kInf;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double d = std::abs(b[i] - a[i]);
    if (d > 0.0) cap = std::min(cap, limits.axis_velocity[i] * l / d);
  }
  return cap;
}

void MotionLimits::validate() const {
  PKM_CHECK(std::isfinite(max_joint_velocity) && max_joint_velocity > 0.0,
            "max joint velocity must be > 0 (got {})",
            max_joint_velocity);
  PKM_CHECK(std::isfinite(max_joint_acceleration) && max_joint_acceleration > 0.0,
            "max joint acceleration must be > 0 (got {})",
            max_joint_acceleration);
  PKM_CHECK(
      std::isfinite(rapid_rate) && rapid_rate > 0.0, "rapid rate must be > 0 (got {})", rapid_rate);
  rapid_axes.validate();
}

JointRateLimits JointRateLimits::uniform(const MotionLimits& limits) {
  JointRateLimits r;
  r.max_velocity.setConstant(limits.max_joint_velocity);
  r.max_acceleration.setConstant(limits.max_joint_acceleration);
  r.rapid_rate = limits.rapid_rate;
  r.rapid_axes = limits.rapid_axes;
  return r;
}

void JointRateLimits::validate() const {
  for (int j = 0; j < kinematics::kStruts; ++j) {
    PKM_CHECK(
        max_velocity(j) > 0.0, "joint {} velocity limit must be > 0 (got {})", j, max_velocity(j));
    PKM_CHECK(max_acceleration(j) > 0.0,
              "joint {} acceleration limit must be > 0 (got {})",
              j,
              max_acceleration(j));
  }
  PKM_CHECK(
      std::isfinite(rapid_rate) && rapid_rate > 0.0, "rapid rate must be > 0 (got {})", rapid_rate);
  rapid_axes.validate();
}

double segmentLength(const Axes& a, const Axes& b) {
  const double l = std::hypot(b[0] - a[0], b[1] - a[1], b[2] - a[2]);
  if (l > 0.0) return l;
  return std::hypot(b[3] - a[3], b[4] - a[4], b[5] - a[5]);
}

double programmedSpeed(const PathPoint& p, const MotionLimits& limits) {
  const bool rapid = p.kind == MoveKind::kRapid || !(p.feed > 0.0);
  return (rapid ? limits.rapid_rate : p.feed) / 60.0;
}

double trapezoidTime(double ds, double v0, double v1, double vmax, double a) {
  if (ds <= 0.0) return 0.0;
  if (!std::isfinite(a)) return ds / vmax;
  // Peak speed of the triangle through v0 and v1: (vp² − v0²)/2a + (vp² − v1²)/2a = ds.
  const double vp = std::min(vmax, std::sqrt((2.0 * a * ds + v0 * v0 + v1 * v1) / 2.0));
  const double d_acc = (vp * vp - v0 * v0) / (2.0 * a);
  const double d_dec = (vp * vp - v1 * v1) / (2.0 * a);
  const double cruise = std::max(0.0, ds - d_acc - d_dec);
  return (vp - v0) / a + (vp - v1) / a + (vp > 0.0 ? cruise / vp : 0.0);
}

std::vector<PathDwell> dwellsOnPath(const std::vector<PathPoint>& points,
                                    const std::vector<DwellEvent>& dwells) {
  std::vector<PathDwell> r;
  r.reserve(dwells.size());
  std::size_t i = 0;  // dwells come in program order: one pass
  for (const DwellEvent& d : dwells) {
    while (i + 1 < points.size() && points[i + 1].move < d.after_moves) ++i;
    r.push_back({i, d.seconds});
  }
  return r;
}

CycleTime estimateCycleTime(const std::vector<PathPoint>& points,
                            const std::vector<kinematics::StrutVector>& q,
                            const MotionLimits& limits,
                            const std::vector<PathDwell>& dwells) {
  limits.validate();
  return estimateCycleTime(points, q, JointRateLimits::uniform(limits), dwells);
}

CycleTime estimateCycleTime(const std::vector<PathPoint>& points,
                            const std::vector<kinematics::StrutVector>& q,
                            const JointRateLimits& limits,
                            const std::vector<PathDwell>& dwells) {
  limits.validate();
  // Rates in units of each joint's limit: |dq_j/ds|/vmax_j and |dq_j/ds|/amax_j (0 when
  // unlimited), so every joint's limit becomes 1.
  const kinematics::StrutVector inv_v = limits.max_velocity.cwiseInverse();
  const kinematics::StrutVector inv_a = limits.max_acceleration.cwiseInverse();
  MotionLimits path;
  path.rapid_rate = limits.rapid_rate;
  PKM_CHECK(points.size() == q.size(), "{} points but {} joint vectors", points.size(), q.size());
  CycleTime r;
  const std::size_t n = points.size();
  r.t.assign(n, 0.0);
  std::vector<double> wait(n, 0.0);  // dwell at each point
  for (const PathDwell& d : dwells) {
    PKM_CHECK(d.point < n && d.seconds >= 0.0 && std::isfinite(d.seconds),
              "a dwell of {} s at point {} of {}",
              d.seconds,
              d.point,
              n);
    wait[d.point] += d.seconds;
    r.dwell += d.seconds;
  }
  if (n < 2) {
    r.total = r.dwell;
    return r;
  }
  // Per sub-segment k (from point k−1 to k): length, speed cap, acceleration cap, dq/ds.
  std::vector<double> ds(n, 0.0), vcap(n, 0.0), acap(n, kInf);
  std::vector<kinematics::StrutVector> dqds(n, kinematics::StrutVector::Zero());
  for (std::size_t k = 1; k < n; ++k) {
    ds[k] = segmentLength(points[k - 1].pos, points[k].pos);
    vcap[k] = programmedSpeed(points[k], path);
    if (points[k].kind == MoveKind::kRapid)
      vcap[k] =
          std::min(vcap[k], rapidSpeedCap(points[k - 1].pos, points[k].pos, limits.rapid_axes));
    if (ds[k] <= 0.0) continue;
    dqds[k] = (q[k] - q[k - 1]) / ds[k];
    const double gv = dqds[k].cwiseAbs().cwiseProduct(inv_v).maxCoeff();  // per path unit
    const double ga = dqds[k].cwiseAbs().cwiseProduct(inv_a).maxCoeff();
    if (gv > 0.0) vcap[k] = std::min(vcap[k], 1.0 / gv);
    if (ga > 0.0) acap[k] = 1.0 / ga;
  }
  // Speed bound at each point: rest at both ends; between sub-segments the lower cap and the
  // joint-acceleration bound v² · |Δ(dq/ds)| / ds_mean <= a_max.
  std::vector<double> v(n, 0.0);
  for (std::size_t k = 1; k + 1 < n; ++k) {
    double vk = std::min(vcap[k], vcap[k + 1]);
    const double mean = 0.5 * (ds[k] + ds[k + 1]);
    if (mean > 0.0) {
      const double jump = (dqds[k + 1] - dqds[k]).cwiseAbs().cwiseProduct(inv_a).maxCoeff() / mean;
      if (jump > 0.0) vk = std::min(vk, std::sqrt(1.0 / jump));
    }
    v[k] = wait[k] > 0.0 ? 0.0 : vk;  // a dwell is an exact stop
  }
  for (std::size_t k = 1; k < n; ++k)  // forward: what can be reached by accelerating
    v[k] = std::min(v[k], reach(v[k - 1], acap[k], ds[k]));
  for (std::size_t k = n - 1; k >= 1; --k)  // backward: what can still be stopped
    v[k - 1] = std::min(v[k - 1], reach(v[k], acap[k], ds[k]));
  for (std::size_t k = 1; k < n; ++k)
    r.t[k] = r.t[k - 1] + wait[k - 1] + trapezoidTime(ds[k], v[k - 1], v[k], vcap[k], acap[k]);
  r.total = r.t.back() + wait[n - 1];
  return r;
}

}  // namespace pkm::cnc
