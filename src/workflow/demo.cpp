// `pkm demo` (demo.hpp): the hexapod round trip along a 5-axis path.
#include "pkm/workflow/demo.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/io/machine_description.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/hexapod_checks.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::workflow {
namespace {

namespace kin = pkm::kinematics;

/// A smooth path around home: a circle of radius `r` in XY, z oscillating, tool tilted up to `tilt`
/// (a, b) and yawed, sampled at n points.
kin::PoseRpy pathPose(const kin::PoseRpy& home, double r, double tilt, int n, int k) {
  const double t = 2.0 * std::numbers::pi * k / n;
  kin::PoseRpy p = home;
  p.position += Eigen::Vector3d(r * std::cos(t) - r, r * std::sin(t), 0.25 * r * std::sin(3 * t));
  p.rpy +=
      Eigen::Vector3d(tilt * std::sin(t), tilt * std::cos(2 * t) - tilt, 0.5 * tilt * std::sin(t));
  return p;
}

/// IK and every check along the path; returns the readings.
std::vector<kin::StrutVector> checkPath(const kin::HexapodModel& model, io::HexapodDemoReport& r) {
  kin::HexapodData data(model);
  r.min_condition = r.min_stroke_margin = r.min_angle_margin = INFINITY;
  std::vector<kin::StrutVector> readings(static_cast<std::size_t>(r.points));
  for (int k = 0; k < r.points; ++k) {
    const kin::HexapodCheckResult c =
        kin::checkPose(model, data, pathPose(model.home, r.radius, r.tilt, r.points, k));
    readings[static_cast<std::size_t>(k)] = c.readings;
    ++r.statuses[std::string(c.status())];
    r.min_condition = std::min(r.min_condition, c.condition_number);
    r.max_condition = std::max(r.max_condition, c.condition_number);
    r.min_stroke_margin = std::min(r.min_stroke_margin, c.stroke_margin.minCoeff());
    r.min_angle_margin = std::min(
        {r.min_angle_margin, c.base_angle_margin.minCoeff(), c.platform_angle_margin.minCoeff()});
  }
  return readings;
}

/// FK back along the path, each solve seeded by the previous solution (home after a failure).
void solvePath(const io::HexapodMachine& machine,
               const std::vector<kin::StrutVector>& readings,
               io::HexapodDemoReport& r) {
  const kin::HexapodModel& model = machine.model;
  kin::HexapodData data(model);
  kin::PoseRpy seed = model.home;
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < r.points; ++k) {
    const kin::FkSummary s = kin::forwardKinematics(
        model, data, readings[static_cast<std::size_t>(k)], seed, machine.fk);
    ++r.iterations[s.iterations];
    if (!s.ok()) {
      seed = model.home;
      continue;
    }
    ++r.converged;
    seed = data.pose;
    const kin::PoseRpy truth = pathPose(model.home, r.radius, r.tilt, r.points, k);
    r.max_position_error =
        std::max(r.max_position_error, (data.pose.position - truth.position).norm());
    const Eigen::Matrix3d dR =
        geometry::rotationFromRpy(data.pose.rpy) * geometry::rotationFromRpy(truth.rpy).transpose();
    r.max_rotation_error = std::max(r.max_rotation_error, geometry::so3Log(dR).norm());
    r.max_residual = std::max(r.max_residual, s.max_residual);
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.pass = r.converged == r.points && r.max_residual <= machine.fk.tolerance;
}

}  // namespace

void DemoRequest::validate() const {
  PKM_CHECK(points >= 2, "--points must be at least 2, got {}", points);
}

DemoResult runDemo(const DemoRequest& request, const RunControl& control) {
  request.validate();
  const auto t0 = std::chrono::steady_clock::now();
  const auto stage = [&](std::size_t index, const char* name, const std::string& message) {
    control.checkCancelled();
    control.report({name,
                    index,
                    2,
                    std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                    message});
    control.checkCancelled();
  };
  io::HalReadOptions hal;
  if (!request.ini.empty()) hal.ini_path = request.ini;
  const io::HexapodMachine machine = io::loadHexapodMachine(request.machine, hal);
  control.note(machine.notices);
  stage(1, "hexapod", "hexapod round trip");
  DemoResult result;
  io::HexapodDemoReport& r = result.hexapod;
  r.description = io::describeHexapodMachine(machine);
  r.unit = machine.model.unit;
  r.points = request.points;
  r.radius = 0.4 * machine.model.characteristicLength();
  r.tilt = degToRad(10.0);
  r.condition_limit = machine.model.max_condition;
  solvePath(machine, checkPath(machine.model, r), r);
  if (request.machine == "default") {
    stage(2, "exechon", "Exechon round trip");
    result.exechon = runExechonDemo(std::min(request.points, 5000));
  }
  return result;
}

}  // namespace pkm::workflow
