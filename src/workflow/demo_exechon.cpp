// The Exechon part of `pkm demo` (demo.hpp): on the built-in hybrid machine mxt700s-like, a
// 5-axis tool path through tool IK and back through FK, the dependent rotational motion along a
// ring-gauge circle (Lee et al. 2019), and the volumetric error map of the MXT700S parallelism
// paper's squareness and PDGE values.
#include <chrono>
#include <cmath>
#include <numbers>

#include "pkm/core/units.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/exechon_checks.hpp"
#include "pkm/kinematics/exechon_drm.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"
#include "pkm/kinematics/hybrid_chain.hpp"
#include "pkm/workflow/demo.hpp"

namespace pkm::workflow {
namespace {

namespace kin = pkm::kinematics;

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

/// Tool IK and checks along the path, then FK back; false when a pose has no IK solution.
bool runPath(const io::ExechonMachine& machine, io::ExechonDemoReport& r) {
  const kin::ExechonModel& model = machine.model;
  kin::ExechonData data(model);
  kin::ExechonConfiguration previous = model.home;
  std::vector<kin::ExechonJoints> joints;
  for (int k = 0; k < r.points; ++k) {
    const kin::ExechonCheckResult c =
        kin::checkToolPose(model, data, toolPathPose(r.points, k), previous);
    if (c.solver_status != "ok") return false;
    if (!c.ok()) ++r.violations;
    previous = kin::configurationOf(data);
    joints.push_back(kin::jointsOf(data));
  }
  kin::ExechonConfiguration seed = model.home;
  const auto t0 = std::chrono::steady_clock::now();
  for (int k = 0; k < r.points; ++k) {
    const kin::FkSummary s = kin::toolForwardKinematics(
        model, data, joints[static_cast<std::size_t>(k)], seed, machine.fk);
    if (!s.ok()) {
      seed = model.home;
      continue;
    }
    ++r.converged;
    seed = kin::configurationOf(data);
    r.max_iterations = std::max(r.max_iterations, s.iterations);
    const kin::ExechonToolPose truth = toolPathPose(r.points, k);
    r.max_position_error =
        std::max(r.max_position_error, (data.world_p_tool - truth.position).norm());
    r.max_direction_error =
        std::max(r.max_direction_error, (data.world_u_tool - truth.direction.normalized()).norm());
  }
  r.us_per_solve =
      1e6 * std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() / r.points;
  return true;
}

/// φ_DRM along a 40 mm master ring with a vertical tool, as in Lee et al. (2019).
void runDrmCircle(const kin::ExechonModel& model, io::ExechonDemoReport& r) {
  kin::ExechonData data(model);
  kin::DrmCircleOptions opt;
  opt.centre = {0.0, 0.0, -100.0};
  opt.radius = 20.0;
  opt.step = degToRad(5.0);
  const kin::DrmCircleResult c = kin::sampleDrmCircle(model, data, opt);
  r.drm_status = std::string(kin::toString(c.status));
  r.drm_max_phi = c.max_abs_phi;
  r.drm_max_fit_deviation = c.max_fit_deviation;
}

/// The volumetric error over X2 0..4000 × Y ±300 × Z ±200 mm, and the parallelism of the PKM's Y
/// to Y2 (MXT700S parallelism paper, §3.1): the z deviation over a 600 mm PKM y stroke.
void runVolumetric(const kin::HybridMachineModel& model,
                   const kin::GeometricErrors& errors,
                   io::ExechonDemoReport& r) {
  for (double x = 0.0; x <= 4000.0; x += 500.0)
    for (double y = -300.0; y <= 300.0; y += 150.0)
      for (double z = -200.0; z <= 200.0; z += 100.0) {
        const kin::HybridCommand c = kin::hybridCommandCentred(model, Eigen::Vector3d(x, y, z));
        const Eigen::Vector3d dp = kin::hybridVolumetricError(model, errors, c);
        const Eigen::Vector3d lin = kin::hybridVolumetricErrorLinear(model, errors, c);
        r.max_dp = std::max(r.max_dp, dp.norm());
        r.max_dp_linear = std::max(r.max_dp_linear, (dp - lin).norm());
        ++r.volumetric_points;
      }
  kin::HybridCommand a, b;
  a.pkm = {0.0, -300.0, 0.0};
  b.pkm = {0.0, 300.0, 0.0};
  r.parallelism_dz = kin::hybridVolumetricError(model, errors, b).z() -
                     kin::hybridVolumetricError(model, errors, a).z();
  r.sx_p = errors.squareness.sx_p;
}

}  // namespace

io::ExechonDemoReport runExechonDemo(int points) {
  const io::ExechonMachine machine = io::loadExechonMachine(io::kDefaultExechonMachine);
  io::ExechonDemoReport r;
  r.machine = machine.model.name;
  r.source = machine.source;
  r.x2_min = machine.hybrid->x2_stroke.min;
  r.x2_max = machine.hybrid->x2_stroke.max;
  r.y2_min = machine.hybrid->y2_stroke.min;
  r.y2_max = machine.hybrid->y2_stroke.max;
  r.points = points;
  r.path_solved = runPath(machine, r);
  r.pass = r.path_solved && r.converged == points && r.max_position_error < 1e-9 &&
           r.max_direction_error < 1e-9;
  runDrmCircle(machine.model, r);
  runVolumetric(*machine.hybrid, io::loadGeometricErrors("mxt700s-seed000"), r);
  return r;
}

}  // namespace pkm::workflow
