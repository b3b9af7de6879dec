// The Exechon part of `pkm demo`: on the built-in hybrid machine mxt700s-like, a 5-axis tool path
// through tool IK and back through FK, the dependent rotational motion along a ring-gauge circle
// (seed 003), and the volumetric error map of seed 000's squareness and PDGE values.
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <numbers>

#include "cli_common.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/exechon_checks.hpp"
#include "pkm/kinematics/exechon_drm.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"
#include "pkm/kinematics/hybrid_chain.hpp"

namespace pkm::cli {

namespace kin = pkm::kinematics;

namespace {

/// Tool pose k of n on a path in the PKM volume: a 150 mm circle with a z wave, the tool leaning up
/// to 15 deg from the vertical and swinging around.
kin::ExechonToolPose toolPathPose(int n, int k) {
  const double t = 2.0 * std::numbers::pi * k / n;
  const double lean = degToRad(15.0) * std::sin(t), swing = 2.0 * t;
  kin::ExechonToolPose p;
  p.position = {150.0 * std::cos(t), 150.0 * std::sin(t), 60.0 * std::sin(3.0 * t)};
  p.direction = {
      std::sin(lean) * std::cos(swing), std::sin(lean) * std::sin(swing), -std::cos(lean)};
  return p;
}

bool runPath(const io::ExechonMachine& machine, int points) {
  const kin::ExechonModel& model = machine.model;
  kin::ExechonData data(model);
  kin::ExechonConfiguration previous = model.home;
  std::vector<kin::ExechonJoints> joints;
  int violations = 0;
  for (int k = 0; k < points; ++k) {
    const kin::ExechonCheckResult c =
        kin::checkToolPose(model, data, toolPathPose(points, k), previous);
    if (c.solver_status != "ok") return false;
    if (!c.ok()) ++violations;
    previous = kin::configurationOf(data);
    joints.push_back(kin::jointsOf(data));
  }
  kin::ExechonConfiguration seed = model.home;
  double max_p = 0.0, max_u = 0.0;
  int failures = 0, max_iter = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < points; ++k) {
    const kin::FkSummary s = kin::toolForwardKinematics(
        model, data, joints[static_cast<std::size_t>(k)], seed, machine.fk);
    if (!s.ok()) {
      ++failures;
      seed = model.home;
      continue;
    }
    seed = kin::configurationOf(data);
    max_iter = std::max(max_iter, s.iterations);
    const kin::ExechonToolPose truth = toolPathPose(points, k);
    max_p = std::max(max_p, (data.world_p_tool - truth.position).norm());
    max_u = std::max(max_u, (data.world_u_tool - truth.direction.normalized()).norm());
  }
  const double us =
      1e6 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / points;
  fmt::print(
      "  tool path    {} poses (150 mm circle, z wave, tool leaning up to 15 deg): {} outside a "
      "limit\n",
      points,
      violations);
  fmt::print("  FK (servo)   {} of {} converged, at most {} Newton steps, {:.2f} us per solve\n",
             points - failures,
             points,
             max_iter,
             us);
  fmt::print("  round trip   max |p_FK - p| = {:.3g} mm, max |u_FK - u| = {:.3g}\n", max_p, max_u);
  return failures == 0 && max_p < 1e-9 && max_u < 1e-9;
}

void runDrmCircle(const kin::ExechonModel& model) {
  kin::ExechonData data(model);
  kin::DrmCircleOptions opt;
  opt.centre = {0.0, 0.0, -100.0};
  opt.radius = 20.0;  // a 40 mm master ring, as in seed 003
  opt.step = degToRad(5.0);
  const kin::DrmCircleResult r = kin::sampleDrmCircle(model, data, opt);
  if (!r.ok()) {
    fmt::print("  DRM          circle failed: {}\n", kin::toString(r.status));
    return;
  }
  fmt::print(
      "  DRM          40 mm ring, vertical tool: max |phi_DRM| {:.3f} deg; 5th-order fit (seed 003 "
      "eq. 10) "
      "max deviation {:.4f} deg (paper: < 0.1 deg on its machine)\n",
      radToDeg(r.max_abs_phi),
      radToDeg(r.max_fit_deviation));
}

void runVolumetric(const kin::HybridMachineModel& model, const kin::GeometricErrors& errors) {
  double max_dp = 0.0, max_lin = 0.0, max_y_slope_dz = 0.0;
  int n = 0;
  for (double x = 0.0; x <= 4000.0; x += 500.0)
    for (double y = -300.0; y <= 300.0; y += 150.0)
      for (double z = -200.0; z <= 200.0; z += 100.0) {
        const kin::HybridCommand c = kin::hybridCommandCentred(model, Eigen::Vector3d(x, y, z));
        const Eigen::Vector3d dp = kin::hybridVolumetricError(model, errors, c);
        const Eigen::Vector3d lin = kin::hybridVolumetricErrorLinear(model, errors, c);
        max_dp = std::max(max_dp, dp.norm());
        max_lin = std::max(max_lin, (dp - lin).norm());
        ++n;
      }
  // Parallelism of the PKM's Y to Y2 (seed 000 §3.1): z deviation over a 600 mm PKM y stroke.
  kin::HybridCommand a, b;
  a.pkm = {0.0, -300.0, 0.0};
  b.pkm = {0.0, 300.0, 0.0};
  max_y_slope_dz = kin::hybridVolumetricError(model, errors, b).z() -
                   kin::hybridVolumetricError(model, errors, a).z();
  fmt::print(
      "  volumetric   seed 000 errors over {} points of X2 0..4000 x Y 600 x Z 400 mm: max |dp| "
      "{:.3f} mm; "
      "exact vs first-order model differ by at most {:.2g} mm\n",
      n,
      max_dp,
      max_lin);
  fmt::print("  parallelism  PKM Y over 600 mm vs Y2: dz {:.3f} mm (sxP = {:.2f} mrad)\n",
             max_y_slope_dz,
             1e3 * errors.squareness.sx_p);
}

}  // namespace

bool runExechonDemo(int points) {
  const io::ExechonMachine machine = io::loadExechonMachine(io::kDefaultExechonMachine);
  fmt::print(
      "\nExechon       {} ({}): tripod with C/A wrist on X2 {:g}..{:g} mm and Y2 {:g}..{:g} mm\n",
      machine.model.name,
      machine.source,
      machine.hybrid->x2_stroke.min,
      machine.hybrid->x2_stroke.max,
      machine.hybrid->y2_stroke.min,
      machine.hybrid->y2_stroke.max);
  const bool ok = runPath(machine, points);
  runDrmCircle(machine.model);
  runVolumetric(*machine.hybrid, io::loadGeometricErrors("mxt700s-seed000"));
  fmt::print("  result       {}\n", ok ? "PASS: tool FK(IK(pose)) returns every pose" : "FAIL");
  return ok;
}

}  // namespace pkm::cli
