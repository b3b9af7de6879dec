#include "pkm/cnc/exechon_path.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "csv_field.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/kinematics/exechon_drm.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"

namespace pkm::cnc {
namespace {
namespace kin = kinematics;

/// Newton iterations of the wrist-axes solve before it gives up, and the iteration from which
/// the Jacobian is refreshed by finite differences at every step.
constexpr int kMaxWristAxesIterations = 50;
constexpr int kRefreshJacobianAfter = 4;
/// Finite-difference step of that Jacobian, relative to the characteristic length.
constexpr double kJacobianStep = 1e-7;
/// Convergence of the wrist-axes solve, relative to the machine's characteristic length: the
/// tool point error is below kWristAxesTolerance, or below kWristAxesFloor and no longer falling
/// (rounding).
constexpr double kWristAxesTolerance = 1e-14;
constexpr double kWristAxesFloor = 1e-12;
}  // namespace

std::string_view toString(ExechonOrientation o) {
  return o == ExechonOrientation::kToolVector ? "vector" : "axes";
}

ExechonOrientation parseExechonOrientation(std::string_view text) {
  if (text == "vector") return ExechonOrientation::kToolVector;
  if (text == "axes") return ExechonOrientation::kWristAxes;
  throw InvalidArgument(
      fmt::format("orientation must be 'vector' or 'axes' (got '{}')", std::string(text)));
}

Eigen::Vector3d toolDirectionFromAngles(double a_deg, double c_deg) {
  const double a = degToRad(a_deg), c = degToRad(c_deg);
  return {-std::sin(c) * std::sin(a), std::cos(c) * std::sin(a), -std::cos(a)};
}

InterpolationOptions exechonInterpolation(const kin::ExechonModel& model, double tolerance) {
  PKM_CHECK(
      tolerance > 0.0 && std::isfinite(tolerance), "tolerance must be > 0 (got {})", tolerance);
  model.validate();
  const double mm = millimetresPer(model.unit);
  kin::ExechonData data(model);
  kin::evaluateConfiguration(model, data, model.home);
  double l_min = std::numeric_limits<double>::infinity();
  for (int i = 0; i < kin::kExechonLegs; ++i) {
    const auto& leg = model.legs[static_cast<std::size_t>(i)];
    const double shortest = leg.length_offset + leg.min_reading;
    l_min = std::min(l_min, std::isfinite(shortest) && shortest > 0.0 ? shortest : data.lengths[i]);
  }
  // Farthest platform joint from the wrist point S, at home (a rigid-body distance).
  double r_joint = 0.0;
  const Eigen::Vector3d& s = data.zoppi_p_S;
  for (const auto& p : data.zoppi_p_platform_joint) r_joint = std::max(r_joint, (p - s).norm());
  const double r = (std::abs(model.wrist.tool_length) + r_joint) * mm;
  InterpolationOptions o;
  o.tolerance = tolerance;
  o.max_step = 0.5 * std::sqrt(8.0 * tolerance * l_min * mm);
  if (r > tolerance / 4.0)
    o.max_angle_step = radToDeg(2.0 * std::acos(1.0 - tolerance / (4.0 * r)));
  return o;
}

ExechonJointConverter::ExechonJointConverter(const kin::ExechonModel& model,
                                             ExechonOrientation orientation)
    : model_(&model),
      orientation_(orientation),
      data_(model),
      previous_(model.home),
      zoppi_T_world_(model.world_T_zoppi.inverse(Eigen::Isometry)) {
  model.validate();
  kin::evaluateConfiguration(model, data_, model.home);
  last_joints_ << data_.readings, radToDeg(model.home.c), radToDeg(model.home.a), 0.0;
}

kin::ExechonIkStatus ExechonJointConverter::solveVector(const Eigen::Vector3d& p,
                                                        const Eigen::Vector3d& u) {
  kin::ExechonToolPose target;
  target.position = p;
  target.direction = u;
  return kin::toolInverseKinematics(*model_, data_, target, previous_);
}

kin::ExechonIkStatus ExechonJointConverter::toolPointError(const Eigen::Vector3d& world_p_S,
                                                           const Eigen::Vector3d& p,
                                                           const Eigen::Vector3d& platform_u_tool,
                                                           kin::ExechonConfiguration& cfg,
                                                           Eigen::Vector3d& r) {
  const kin::ExechonModel& m = *model_;
  const kin::ExechonIkStatus st =
      kin::tripodInverseKinematicsNearest(m, data_, zoppi_T_world_ * world_p_S, cfg.e);
  if (st != kin::ExechonIkStatus::kOk) return st;
  cfg.e = data_.e;
  r = data_.world_p_S + m.wrist.tool_length * (data_.world_T_platform.linear() * platform_u_tool) -
      p;
  return st;
}

kin::ExechonIkStatus ExechonJointConverter::solveAxes(const Eigen::Vector3d& p,
                                                      double c,
                                                      double a) {
  const kin::ExechonModel& m = *model_;
  // Newton on F(S) = S + L·u(S) − p (u the tool direction the readings give on the platform at
  // the wrist point S), with the inverse Jacobian of the previous point (it changes little along
  // a path) and a finite-difference one when there is none or convergence slows. The readings
  // are fixed, so the tool direction in the platform frame is too.
  const Eigen::Vector3d platform_u_tool = kin::toolRotationInPlatform(m.wrist, c, a).col(2);
  kin::ExechonConfiguration cfg{previous_.e, c, a};
  // data_ holds the previous solution's tripod pose: the first guess keeps it.
  Eigen::Vector3d world_p_S =
      p - m.wrist.tool_length * (data_.world_T_platform.linear() * platform_u_tool);
  const double tol = kWristAxesTolerance * m.characteristicLength();
  const double floor = kWristAxesFloor * m.characteristicLength();
  double last = std::numeric_limits<double>::infinity();
  Eigen::Vector3d r;
  for (int it = 0; it < kMaxWristAxesIterations; ++it) {
    kin::ExechonIkStatus st = toolPointError(world_p_S, p, platform_u_tool, cfg, r);
    if (st != kin::ExechonIkStatus::kOk) return st;
    const double err = r.norm();
    if (err <= tol || (err <= floor && err >= last)) {
      kin::setWristReadings(m, data_, c, a);  // data_ holds the tripod at this world_p_S
      return kin::ExechonIkStatus::kOk;
    }
    if (!have_jacobian_ || it >= kRefreshJacobianAfter) {
      const kin::ExechonConfiguration at = cfg;
      const double h = kJacobianStep * m.characteristicLength();
      Eigen::Matrix3d J;
      for (int k = 0; k < 3; ++k) {
        kin::ExechonConfiguration probe = at;
        Eigen::Vector3d rk;
        st =
            toolPointError(world_p_S + h * Eigen::Vector3d::Unit(k), p, platform_u_tool, probe, rk);
        if (st != kin::ExechonIkStatus::kOk) return st;
        J.col(k) = (rk - r) / h;
      }
      bool invertible = false;
      double det = 0.0;
      J.computeInverseAndDetWithCheck(jacobian_inverse_, det, invertible);
      if (!invertible) return kin::ExechonIkStatus::kSingular;
      have_jacobian_ = true;
      cfg = at;
    }
    last = err;
    world_p_S -= jacobian_inverse_ * r;
  }
  return kin::ExechonIkStatus::kSingular;
}

ExechonPathSample ExechonJointConverter::solve(const Axes& pos) {
  ExechonPathSample out;
  const double k = 1.0 / millimetresPer(model_->unit);
  const Eigen::Vector3d p(pos[0] * k, pos[1] * k, pos[2] * k);
  bool finite = true;
  for (double v : pos) finite = finite && std::isfinite(v);
  if (!finite || pos[4] != 0.0) {
    out.status = kin::ExechonIkStatus::kInvalidInput;
  } else if (orientation_ == ExechonOrientation::kToolVector) {
    out.status = solveVector(p, toolDirectionFromAngles(pos[3], pos[5]));
  } else {
    out.status = solveAxes(p, degToRad(pos[5]), degToRad(pos[3]));
  }
  if (!out.ok()) {
    kin::evaluateConfiguration(*model_, data_, previous_);  // data back at the last solution
    out.joints = last_joints_;
    return out;
  }
  previous_ = kin::configurationOf(data_);
  if (!have_reference_) {
    reference_R_ = data_.world_R_tool;
    have_reference_ = true;
  }
  out.config = previous_;
  out.readings = data_.readings;
  out.direction = data_.world_u_tool;
  out.drm = kin::dependentRotation(data_.world_R_tool, reference_R_);
  out.joints << data_.readings, radToDeg(data_.c), radToDeg(data_.a), 0.0;
  last_joints_ = out.joints;
  return out;
}

void ExechonJointConverter::solveAll(const std::vector<PathPoint>& points,
                                     std::vector<ExechonPathSample>& out) {
  out.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) out[i] = solve(points[i].pos);
}

void appendExechonJointCsv(std::string& out,
                           const PathPoint& point,
                           double t,
                           const ExechonPathSample& sample) {
  detail::appendCsvIndex(out, point.line);
  detail::appendCsvField(out, t);
  for (double v : point.pos) detail::appendCsvField(out, v);
  if (!sample.ok()) {
    out.append(",,,,,,,,,\n");
    return;
  }
  for (int i = 0; i < 3; ++i) detail::appendCsvField(out, sample.readings[i]);
  detail::appendCsvField(out, radToDeg(sample.config.c));
  detail::appendCsvField(out, radToDeg(sample.config.a));
  for (int i = 0; i < 3; ++i) detail::appendCsvField(out, sample.direction[i]);
  detail::appendCsvField(out, radToDeg(sample.drm));
  out.push_back('\n');
}

}  // namespace pkm::cnc
