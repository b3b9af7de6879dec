#include "pkm/cnc/joint_path.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "csv_field.hpp"
#include "pkm/core/error.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::cnc {

kinematics::PoseRpy poseFromAxes(const Axes& pos, LengthUnit unit) {
  const double k = 1.0 / millimetresPer(unit);
  kinematics::PoseRpy p;
  p.position = Eigen::Vector3d(pos[0] * k, pos[1] * k, pos[2] * k);
  p.rpy = Eigen::Vector3d(degToRad(pos[3]), degToRad(pos[4]), degToRad(pos[5]));
  return p;
}

InterpolationOptions jointSpaceInterpolation(const kinematics::HexapodModel& model,
                                             double tolerance) {
  PKM_CHECK(
      tolerance > 0.0 && std::isfinite(tolerance), "tolerance must be > 0 (got {})", tolerance);
  const double mm = millimetresPer(model.unit);
  double l_min = std::numeric_limits<double>::infinity(), r_max = 0.0;
  for (int i = 0; i < kinematics::kStruts; ++i) {
    const auto& s = model.struts[static_cast<std::size_t>(i)];
    const double shortest = s.length_offset + s.min_reading;
    if (std::isfinite(shortest) && shortest > 0.0) l_min = std::min(l_min, shortest * mm);
    r_max = std::max(r_max, model.effectivePlatform(i).norm() * mm);
  }
  if (!std::isfinite(l_min)) {  // no stroke: the joint distances at home
    kinematics::HexapodData data(model);
    kinematics::inverseKinematics(model, data, model.home);
    l_min = data.joint_distance.minCoeff() * mm;
  }
  InterpolationOptions o;
  o.tolerance = tolerance;
  o.max_step = 0.5 * std::sqrt(8.0 * tolerance * l_min);
  if (r_max > tolerance / 4.0)
    o.max_angle_step = radToDeg(2.0 * std::acos(1.0 - tolerance / (4.0 * r_max)));
  return o;
}

HexapodJointConverter::HexapodJointConverter(const kinematics::HexapodModel& model)
    : model_(&model), data_(model) {
  model.validate();
}

const kinematics::StrutVector& HexapodJointConverter::solve(const Axes& pos) {
  return kinematics::inverseKinematics(*model_, data_, poseFromAxes(pos, model_->unit));
}

void HexapodJointConverter::solveAll(const std::vector<PathPoint>& points,
                                     std::vector<kinematics::StrutVector>& q) {
  q.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) q[i] = solve(points[i].pos);
}

void appendJointCsv(std::string& out,
                    const PathPoint& point,
                    double t,
                    const kinematics::StrutVector& q) {
  detail::appendCsvIndex(out, point.line);
  detail::appendCsvField(out, t);
  for (double v : point.pos) detail::appendCsvField(out, v);
  for (int i = 0; i < kinematics::kStruts; ++i) detail::appendCsvField(out, q(i));
  out.push_back('\n');
}

}  // namespace pkm::cnc
