// `pkm plan-poses` for an Exechon: tracker points chosen by an observability index among tool
// poses that the machine reaches within every limit (docs/calibration.md, "Pose planning").
#include <fmt/format.h>

#include "pkm/calibration/exechon_pose_planning.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/exechon_data.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"
#include "pkm/simulation/exechon_tracker.hpp"
#include "plan_poses_detail.hpp"

namespace pkm::workflow::detail {
namespace {

namespace cal = pkm::calibration;
namespace kin = pkm::kinematics;

/// One candidate: the tool pose that is commanded and the configuration that reaches it.
struct Candidate {
  kin::ExechonToolPose pose;
  kin::ExechonConfiguration configuration;
};

/// Tool points uniform in the box about the home tool point, directions uniform within `tilt` of
/// the home direction, kept where the machine reaches them within every limit (the simulator's
/// tracker sampling, without noise).
std::vector<Candidate> sampleCandidates(const kin::ExechonModel& model,
                                        const PlanPosesRequest& request,
                                        const Eigen::Vector3d& target_offset) {
  kin::ExechonData data(model);
  kin::evaluateConfiguration(model, data, model.home);
  const double reach = request.reach > 0.0 ? request.reach : 0.3 * model.characteristicLength();
  simulation::ExechonTrackerSetup setup;
  setup.name = "plan-poses";
  setup.count = request.candidates;
  setup.box_min = data.world_p_tool - Eigen::Vector3d::Constant(reach);
  setup.box_max = data.world_p_tool + Eigen::Vector3d::Constant(reach);
  setup.direction = data.world_u_tool;
  setup.max_tilt = degToRad(request.tilt_deg);
  setup.smr_offset = target_offset;
  simulation::RandomStream rng(request.seed, "plan-poses");
  const auto readings = simulation::simulateExechonTracker(model, model, {}, setup, rng);
  std::vector<Candidate> out;
  out.reserve(readings.size());
  for (const auto& r : readings) {
    PKM_CHECK(
        kin::toolInverseKinematics(model, data, r.command, model.home) == kin::ExechonIkStatus::kOk,
        "plan-poses: a sampled tool pose has no inverse kinematics");
    out.push_back({r.command, kin::configurationOf(data)});
  }
  return out;
}

/// The program's move to configuration `c`: its tool point and wrist readings.
io::ExechonPlanMove moveTo(const kin::ExechonModel& model,
                           kin::ExechonData& data,
                           const kin::ExechonConfiguration& c) {
  kin::evaluateConfiguration(model, data, c);
  return {data.world_p_tool, c.a, c.c};
}

}  // namespace

PlanPosesResult planExechonPoses(const PlanPosesRequest& request, const PlanStages& stages) {
  const io::ExechonMachine machine =
      request.exechon ? *request.exechon : io::loadExechonMachine(request.machine);
  const kin::ExechonModel& model = machine.model;
  if (request.measurement == "pose")
    throw InvalidArgument(
        "--measurement pose: an Exechon plan is for tracker points (--measurement point)");
  PKM_CHECK(request.tilt_deg >= 0.0 && request.tilt_deg <= 90.0 && request.reach >= 0.0,
            "--reach must be >= 0 and --tilt within [0, 90] degrees");
  checkProgram(request);
  const std::vector<double>& t = request.target_offset;
  const Eigen::Vector3d target_offset =
      t.empty() ? Eigen::Vector3d::Zero() : Eigen::Vector3d(t[0], t[1], t[2]);
  stages.enter(1, "candidates", fmt::format("sampling {} candidates", request.candidates));
  const std::vector<Candidate> pool = sampleCandidates(model, request, target_offset);
  std::vector<kin::ExechonConfiguration> configurations;
  configurations.reserve(pool.size());
  for (const Candidate& c : pool) configurations.push_back(c.configuration);
  cal::ExechonPosePlanOptions options;
  options.count = request.count;
  options.index = cal::parseObservabilityIndex(request.index);
  options.target_offset = target_offset;
  stages.enter(2, "plan", fmt::format("choosing {} of {} points", request.count, pool.size()));
  PlanPosesResult result;
  io::PosePlanReport& r = result.report;
  r.plan = cal::planExechonPoses(model, configurations, options);
  r.kind = "exechon";
  r.machine = model.name;
  r.unit = model.unit;
  r.index_label = request.index;
  r.index = options.index;
  r.candidates = pool.size();
  r.parameters = cal::kExechonParameters;
  r.feed = request.feed.value_or(detail::kDefaultFeed);
  kin::ExechonData data(model);
  r.moves.push_back(moveTo(model, data, model.home));
  for (int k : r.plan.chosen) {
    const Candidate& c = pool[static_cast<std::size_t>(k)];
    r.points.push_back(c.pose);
    r.moves.push_back(moveTo(model, data, c.configuration));
  }
  finishPlan(request, stages, result);
  return result;
}

}  // namespace pkm::workflow::detail
