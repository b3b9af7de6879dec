#include "pkm/simulation/touch_probe.hpp"

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <numbers>

#include "pkm/core/error.hpp"
#include "pkm/kinematics/exechon_data.hpp"
#include "pkm/kinematics/exechon_drm.hpp"
#include "pkm/kinematics/exechon_ik.hpp"

namespace pkm::simulation {

namespace {

namespace kin = pkm::kinematics;

constexpr double kTouchTolerance = 1e-12;  // mm: fixed-point convergence of the trigger travel
constexpr int kTouchIterations = 50;

/// Solves one touch (see the file comment of touch_probe.hpp).
class Prober {
 public:
  explicit Prober(const TouchProbeSetup& s) : s_(s), data_(*s.machine) {
    reference_.position = s.offset_ring_center;
    reference_.direction = s.direction.normalized();
  }

  /// φ_DRM at spindle-axis position p relative to the reference pose.
  double drmAt(const Eigen::Vector3d& p) {
    kin::ExechonToolPose pose;
    pose.position = p;
    pose.direction = reference_.direction;
    double phi = 0.0;
    const kin::ExechonIkStatus status =
        kin::dependentRotation(*s_.machine, data_, pose, reference_, &phi);
    PKM_CHECK(status == kin::ExechonIkStatus::kOk,
              "{}: the tool cannot reach ({}, {}, {}) (tool IK: {})",
              s_.name,
              p.x(),
              p.y(),
              p.z(),
              kin::toString(status));
    return phi;
  }

  /// The machine's error motion at command p (identity without a tripod).
  [[nodiscard]] geometry::RigidTransform errorAt(const Eigen::Vector3d& p) const {
    return s_.tripod ? s_.tripod->errorMotion(p) : geometry::RigidTransform::Identity();
  }

  /// Ball centre (x, y) with the spindle axis commanded at p, the stylus turned by `turn` about t
  /// and the tool moved by the error motion `e` (at p, or near it while a touch converges).
  [[nodiscard]] Eigen::Vector2d ball(const Eigen::Vector3d& p,
                                     double turn,
                                     const geometry::RigidTransform& e) const {
    const Eigen::Vector3d d(s_.stylus_offset.x(), s_.stylus_offset.y(), 0.0);
    return (p + e.translation() + e.linear() * (Eigen::AngleAxisd(turn, reference_.direction) * d))
        .head<2>();
  }

  /// The ring's radius less the ball's at the angle of `b` (x, y about the ring's centre).
  [[nodiscard]] double contactRadius(const Eigen::Vector2d& b) const {
    const double R = s_.ring_diameter * (1.0 + s_.ring_expansion) / 2.0;
    const double form = s_.ring_form > 0.0 && b.norm() > 0.0
                            ? 0.5 * s_.ring_form * std::cos(2.0 * std::atan2(b.y(), b.x()))
                            : 0.0;
    return R + form - s_.ball_radius;
  }

  /// Travel along u from `start` until the ball reaches the ring of `centre`, for a turn that is a
  /// function of the current position.
  template <typename Turn>
  double travel(const Eigen::Vector3d& start,
                const Eigen::Vector2d& u,
                const Eigen::Vector3d& centre,
                Turn turn) {
    double t = 0.0;
    for (int it = 0; it < kTouchIterations; ++it) {
      const Eigen::Vector3d p = start + t * Eigen::Vector3d(u.x(), u.y(), 0.0);
      const Eigen::Vector2d b0 = ball(start, turn(p), errorAt(p)) - centre.head<2>();
      const double rho = contactRadius(b0 + t * u);
      const double bu = b0.dot(u);
      const double disc = bu * bu - b0.squaredNorm() + rho * rho;
      PKM_CHECK(disc >= 0.0, "{}: the ball starts outside the ring", s_.name);
      const double next = -bu + std::sqrt(disc);
      const bool done = std::abs(next - t) <= kTouchTolerance;
      t = next;
      if (done) break;
    }
    return t;
  }

  /// One touch with the spindle at `base` (rad), compensated for the DRM or not.
  TouchRecord touch(const std::string& label,
                    int run,
                    const Eigen::Vector3d& start,
                    double approach,
                    const Eigen::Vector3d& centre,
                    double base,
                    bool compensate,
                    RandomStream& rng) {
    const Eigen::Vector2d u(std::cos(approach), std::sin(approach));
    double spindle = base;
    if (compensate) {
      // The spindle is set before the move to cancel φ_DRM at the target, the touch point that a
      // perfectly compensated stylus would reach (Lee et al. 2019, sec. 3.2: DRM angle at the touch
      // position relative to the ring centre).
      const double t0 = travel(start, u, centre, [&](const Eigen::Vector3d&) { return base; });
      spindle = base - drmAt(start + t0 * Eigen::Vector3d(u.x(), u.y(), 0.0));
    }
    const double t =
        travel(start, u, centre, [&](const Eigen::Vector3d& p) { return spindle + drmAt(p); });
    TouchRecord r;
    r.touch = label;
    r.run = run;
    r.approach = approach;
    r.spindle = spindle;
    const Eigen::Vector3d p = start + t * Eigen::Vector3d(u.x(), u.y(), 0.0);
    r.drm = drmAt(p);
    r.ball = ball(p, spindle + r.drm, errorAt(p));
    const double lobe = s_.lobing * std::cos(s_.lobes * (approach - planeTurn(s_, r)));
    const double measured = s_.noise.apply(t + lobe, t, rng);
    r.position = start + measured * Eigen::Vector3d(u.x(), u.y(), 0.0);
    return r;
  }

 private:
  const TouchProbeSetup& s_;
  kin::ExechonData data_;
  kin::ExechonToolPose reference_;
};

}  // namespace

void TouchProbeSetup::validate() const {
  PKM_CHECK(machine != nullptr, "{}: no Exechon machine", name);
  PKM_CHECK(offset_ring_center.allFinite() && circle_ring_center.allFinite() &&
                stylus_offset.allFinite() && direction.allFinite() && std::isfinite(start_angle),
            "{}: non-finite set-up value",
            name);
  PKM_CHECK(direction.norm() > 0.0 && std::abs(direction.x()) <= 1e-12 * direction.norm() &&
                std::abs(direction.y()) <= 1e-12 * direction.norm(),
            "{}: the tool direction must be +z or -z (the ring lies in the xy plane)",
            name);
  PKM_CHECK(std::isfinite(ring_expansion) && ring_expansion > -1.0,
            "{}: ring expansion {} must be finite and > -1",
            name,
            ring_expansion);
  PKM_CHECK(ring_diameter > 0.0 && std::isfinite(ring_diameter),
            "{}: the ring diameter must be > 0",
            name);
  PKM_CHECK(ball_radius > 0.0 && ball_radius < ring_diameter / 2.0,
            "{}: the ball radius must be in (0, ring radius)",
            name);
  PKM_CHECK(2.0 * stylus_offset.norm() < ring_diameter / 2.0 - ball_radius,
            "{}: twice the stylus offset must be smaller than ring radius minus ball radius",
            name);
  PKM_CHECK(circle_points >= 4, "{}: circle_points must be >= 4", name);
  PKM_CHECK(runs >= 1, "{}: runs must be >= 1", name);
  PKM_CHECK(std::isfinite(ring_form) && ring_form >= 0.0 && ring_form < ring_diameter / 4.0,
            "{}: the ring form must be >= 0 and small against the ring",
            name);
  PKM_CHECK(std::isfinite(lobing) && lobing >= 0.0 && lobes >= 1,
            "{}: lobing must be >= 0 and lobes >= 1",
            name);
  noise.validate();
}

double planeTurn(const TouchProbeSetup& setup, const TouchRecord& touch) {
  return (setup.direction.z() > 0.0 ? 1.0 : -1.0) * (touch.spindle + touch.drm);
}

Eigen::Vector2d reportedSurfacePoint(const TouchProbeSetup& setup, const TouchRecord& touch) {
  const Eigen::Vector2d u(std::cos(touch.approach), std::sin(touch.approach));
  return touch.position.head<2>() + setup.stylus_offset + setup.ball_radius * u;
}

TouchProbeResult simulateTouchProbe(const TouchProbeSetup& setup, RandomStream& rng) {
  setup.validate();
  Prober prober(setup);
  TouchProbeResult out;
  constexpr double kPi = std::numbers::pi;
  const Eigen::Vector3d& c1 = setup.offset_ring_center;
  for (int run = 1; run <= setup.runs; ++run) {
    // Spindle 0: centre the ball in x, then in y (the operator's bidirectional touches).
    const TouchRecord px = prober.touch("+x", run, c1, 0.0, c1, 0.0, true, rng);
    const TouchRecord mx = prober.touch("-x", run, c1, kPi, c1, 0.0, true, rng);
    Eigen::Vector3d p1 = c1;
    p1.x() = 0.5 * (px.position.x() + mx.position.x());
    const TouchRecord py = prober.touch("+y", run, p1, kPi / 2.0, c1, 0.0, true, rng);
    const TouchRecord my = prober.touch("-y", run, p1, -kPi / 2.0, c1, 0.0, true, rng);
    p1.y() = 0.5 * (py.position.y() + my.position.y());
    for (const TouchRecord& r : {px, mx, py, my}) out.offset.push_back(r);
    // Spindle reversed (Lee et al. 2019, Fig. 5): the offset shows twice.
    const std::array<std::pair<const char*, double>, 4> moves{
        {{"+x", 0.0}, {"-x", kPi}, {"+y", kPi / 2.0}, {"-y", -kPi / 2.0}}};
    for (const auto& [label, approach] : moves)
      out.offset.push_back(prober.touch(label, run, p1, approach, c1, kPi, true, rng));
  }
  const Eigen::Vector3d& c2 = setup.circle_ring_center;
  for (int run = 1; run <= setup.runs; ++run)
    for (int k = 0; k < setup.circle_points; ++k) {
      const double approach = setup.start_angle + 2.0 * kPi * k / setup.circle_points;
      out.circle_uncompensated.push_back(
          prober.touch("circle", run, c2, approach, c2, 0.0, false, rng));
    }
  for (int run = 1; run <= setup.runs; ++run)
    for (int k = 0; k < setup.circle_points; ++k) {
      const double approach = setup.start_angle + 2.0 * kPi * k / setup.circle_points;
      out.circle_compensated.push_back(
          prober.touch("circle", run, c2, approach, c2, 0.0, true, rng));
    }
  return out;
}

std::vector<TouchProbeRun> runTouchProbes(const std::vector<TouchProbeSetup>& setups,
                                          std::uint64_t seed) {
  std::vector<TouchProbeRun> out;
  for (const TouchProbeSetup& s : setups) {
    RandomStream rng(seed, s.name);
    out.push_back({&s, simulateTouchProbe(s, rng)});
  }
  return out;
}

}  // namespace pkm::simulation
