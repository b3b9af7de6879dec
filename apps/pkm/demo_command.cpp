// `pkm demo`: the main job on the embedded default machines. For now: describe the hexapod, follow
// a 5-axis path through IK, check every pose, solve FK back along it as a servo loop would, and
// summarise accuracy, iterations, limits and speed; then the Exechon part (demo_exechon.cpp).
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <map>
#include <numbers>

#include "cli_common.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_checks.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::cli {

namespace kin = pkm::kinematics;

namespace {

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

void runDemo(const MachineOption& machine_opt, int points) {
  const io::HexapodMachine machine = machine_opt.load();
  const kin::HexapodModel& model = machine.model;
  std::string text;
  describeMachine(machine, text);
  fmt::print("{}\n", text);

  const double scale = model.characteristicLength();
  const double radius = 0.4 * scale;
  const double tilt = degToRad(10.0);
  fmt::print("path         {} poses: circle of radius {:g} {} with z wave, tilt up to {:g} deg\n",
             points,
             radius,
             toString(model.unit),
             2 * radToDeg(tilt));

  kin::HexapodData data(model);
  std::map<std::string, int> statuses;
  std::map<int, int> iteration_hist;
  double max_pos_err = 0, max_ang_err = 0, max_resid = 0, min_cond = INFINITY, max_cond = 0;
  double min_stroke = INFINITY, min_angle = INFINITY;
  int failures = 0;
  std::vector<kin::StrutVector> readings(static_cast<std::size_t>(points));
  for (int k = 0; k < points; ++k) {
    const kin::HexapodCheckResult c =
        kin::checkPose(model, data, pathPose(model.home, radius, tilt, points, k));
    readings[static_cast<std::size_t>(k)] = c.readings;
    ++statuses[std::string(c.status())];
    min_cond = std::min(min_cond, c.condition_number);
    max_cond = std::max(max_cond, c.condition_number);
    min_stroke = std::min(min_stroke, c.stroke_margin.minCoeff());
    min_angle =
        std::min({min_angle, c.base_angle_margin.minCoeff(), c.platform_angle_margin.minCoeff()});
  }
  kin::PoseRpy seed = model.home;
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < points; ++k) {
    const kin::FkSummary s = kin::forwardKinematics(
        model, data, readings[static_cast<std::size_t>(k)], seed, machine.fk);
    ++iteration_hist[s.iterations];
    if (!s.ok()) {
      ++failures;
      seed = model.home;
      continue;
    }
    seed = data.pose;
    const kin::PoseRpy truth = pathPose(model.home, radius, tilt, points, k);
    max_pos_err = std::max(max_pos_err, (data.pose.position - truth.position).norm());
    const Eigen::Matrix3d dR =
        geometry::rotationFromRpy(data.pose.rpy) * geometry::rotationFromRpy(truth.rpy).transpose();
    max_ang_err = std::max(max_ang_err, geometry::so3Log(dR).norm());
    max_resid = std::max(max_resid, s.max_residual);
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  fmt::print("\nsummary\n");
  fmt::print("  IK + checks  status counts:");
  for (const auto& [k, v] : statuses) fmt::print(" {} {}", k, v);
  fmt::print("\n  conditioning scaled Jacobian condition number {:.2f} .. {:.2f} (limit {:g})\n",
             min_cond,
             max_cond,
             model.max_condition);
  fmt::print(
      "  margins      smallest stroke margin {:.3f} {}, smallest joint-angle margin {:.2f} deg\n",
      min_stroke,
      toString(model.unit),
      radToDeg(min_angle));
  fmt::print("  FK (servo)   {} of {} converged; iterations:", points - failures, points);
  for (const auto& [k, v] : iteration_hist) fmt::print(" {}x{}", v, k);
  fmt::print(
      "\n  round trip   max |p_FK - p| = {:.3g} {}, max rotation error = {:.3g} rad, max strut "
      "residual = {:.3g} {}\n",
      max_pos_err,
      toString(model.unit),
      max_ang_err,
      max_resid,
      toString(model.unit));
  fmt::print("  speed        {:.2f} us per forward solve ({} solves in {:.3f} s)\n",
             1e6 * seconds / points,
             points,
             seconds);
  const bool pass = failures == 0 && max_resid <= machine.fk.tolerance;
  fmt::print("  result       {}\n", pass ? "PASS: FK(IK(pose)) returns every pose" : "FAIL");
  const bool exechon_pass =
      machine_opt.spec == "default" ? runExechonDemo(std::min(points, 5000)) : true;
  if (!pass || !exechon_pass) throw std::runtime_error("demo round trip failed");
}

}  // namespace

void addDemoCommand(CLI::App& app) {
  auto opt = std::make_shared<MachineOption>();
  auto points = std::make_shared<int>(20000);
  CLI::App* demo = app.add_subcommand(
      "demo", "describe the default hexapod and run an IK/FK round trip along a path");
  opt->add(*demo);
  demo->add_option("--points", *points, "number of path poses")->check(CLI::Range(2, 10000000));
  demo->callback([opt, points] { runDemo(*opt, *points); });
}

}  // namespace pkm::cli
