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
    : model_(&model), orientation_(orientation), data_(model), previous_(model.home) {
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

kin::ExechonIkStatus ExechonJointConverter::solveAxes(const Eigen::Vector3d& p,
                                                      double c,
                                                      double a) {
  // Newton's method starts from the quadratic extrapolation of the last three solutions (linear
  // of two, or the last one, at the start of a path or after a failed point): along an evenly
  // sampled path its error is third order in the step, and one Newton step reaches the tolerance.
  // A start a multiple of 2·pi away in alpha or beta is the same pose.
  const Eigen::Vector3d& e1 = previous_.e;
  const Eigen::Vector3d start = solved_in_row_ >= 3
                                    ? Eigen::Vector3d(3.0 * (e1 - older_e_[0]) + older_e_[1])
                                : solved_in_row_ == 2 ? Eigen::Vector3d(2.0 * e1 - older_e_[0])
                                                      : e1;
  return kin::toolPointInverseKinematics(*model_, data_, p, c, a, start);
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
    solved_in_row_ = std::min(solved_in_row_, 1);  // no extrapolation across a failed point
    out.joints = last_joints_;
    return out;
  }
  older_e_ = {previous_.e, older_e_[0]};
  solved_in_row_ = std::min(solved_in_row_ + 1, 3);
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
