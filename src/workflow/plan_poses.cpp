// `pkm plan-poses` (plan_poses.hpp): the request, the hexapod planner and the shared stages.
#include "pkm/workflow/plan_poses.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "pkm/calibration/pose_planning.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/simulation/hexapod_workspace.hpp"
#include "pkm/workflow/gcode_run.hpp"
#include "plan_poses_detail.hpp"

namespace pkm::workflow {

namespace cal = pkm::calibration;

void PlanPosesRequest::validate() const {
  PKM_CHECK(count >= 1, "--count must be at least 1, got {}", count);
  PKM_CHECK(
      candidates >= count, "--candidates ({}) must be at least --count ({})", candidates, count);
  static_cast<void>(cal::parseObservabilityIndex(index));
  PKM_CHECK(measurement.empty() || measurement == "pose" || measurement == "point",
            "--measurement '{}': expected pose or point",
            measurement);
  PKM_CHECK(target_offset.empty() || target_offset.size() == 3, "--target-offset: expected x,y,z");
  PKM_CHECK(!(hexapod && exechon),
            "plan-poses: give one loaded machine, not a hexapod and an Exechon");
}

std::string PlanPosesRequest::machineType() const {
  if (hexapod) return "hexapod";
  if (exechon) return "exechon";
  return io::machineTypeOf(machine);
}

namespace detail {

void PlanStages::enter(std::size_t index,
                       const std::string& stage,
                       const std::string& message) const {
  control_.checkCancelled();
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  control_.report({stage, index, 3, elapsed, message});
  control_.checkCancelled();
}

void checkProgram(const PlanPosesRequest& request) {
  if (!request.gcode.empty())
    io::checkOverwrite(request.gcode,
                       request.force ? io::Overwrite::kAllow : io::Overwrite::kRefuse);
}

namespace {

/// The fraction of a joint's velocity limit a lowered feed aims at.
constexpr double kFeedMargin = 0.9;

/// `wanted` rounded down to two significant digits.
double roundDownFeed(double wanted) {
  const double step = std::pow(10.0, std::floor(std::log10(wanted)) - 1.0);
  return std::max(step, std::floor(wanted / step) * step);
}

/// The fastest joint speed of the plan's program at `feed` against its limit: value / limit of
/// `gcode run`'s joint_velocity check (0 when it evaluated nothing).
double jointSpeedRatio(const PlanPosesRequest& request, io::PosePlanReport report, double feed) {
  report.feed = feed;
  GcodeRunRequest run;
  run.program = {"plan-poses program", io::posePlanGcode(report)};
  run.machine = request.machine;
  run.ini = request.ini;
  run.hexapod = request.hexapod;
  run.exechon = request.exechon;
  if (report.kind == "exechon") run.orientation = "axes";
  const GcodeRunResult r = runGcode(run);
  for (const io::GcodeCheckSummary& c : r.report.checks)
    if (c.name == "joint_velocity" && c.enabled && std::isfinite(c.worst.margin) &&
        c.worst.limit > 0.0)
      return c.worst.value / c.worst.limit;
  return 0.0;
}

double programFeed(const PlanPosesRequest& request,
                   const io::PosePlanReport& report,
                   const RunControl& control) {
  if (request.feed) {
    const double ratio = jointSpeedRatio(request, report, *request.feed);
    if (ratio > 1.0)
      control.note(
          {fmt::format("--feed {:g}: a joint would move at {:.3g} times its velocity "
                       "limit (the program's `gcode run` would fail its joint_velocity "
                       "check); F{:g} keeps every joint within it",
                       *request.feed,
                       ratio,
                       roundDownFeed(*request.feed * kFeedMargin / ratio))});
    return *request.feed;
  }
  double feed = kDefaultFeed;
  for (int attempt = 0; attempt < 4; ++attempt) {
    const double ratio = jointSpeedRatio(request, report, feed);
    if (ratio <= 1.0) return feed;
    // Joint speeds scale with the feed: two significant digits, rounded down, with a margin.
    feed = roundDownFeed(feed * kFeedMargin / ratio);
  }
  return feed;
}

}  // namespace

void finishPlan(const PlanPosesRequest& request,
                const PlanStages& stages,
                PlanPosesResult& result) {
  result.csv = io::posePlanCsv(result.report);
  result.summary = io::posePlanSummary(result.report);
  if (stages.control().notice) stages.control().notice(result.summary);
  if (request.gcode.empty()) return;
  stages.enter(3, "program", fmt::format("writing {}", request.gcode));
  result.report.feed = programFeed(request, result.report, stages.control());
  result.gcode = io::posePlanGcode(result.report);
  io::writeFileAtomic(
      request.gcode, result.gcode, request.force ? io::Overwrite::kAllow : io::Overwrite::kRefuse);
}

}  // namespace detail

namespace {

/// Candidates uniform in a box about home, kept where every limit holds.
std::vector<kinematics::PoseRpy> hexapodCandidates(const kinematics::HexapodModel& model,
                                                   const PlanPosesRequest& request) {
  const double reach = request.reach > 0.0 ? request.reach : 0.4 * model.characteristicLength();
  simulation::PoseBox box;
  for (int i = 0; i < 3; ++i) {
    box.lo(i) = model.home.position(i) - reach;
    box.hi(i) = model.home.position(i) + reach;
    box.lo(3 + i) = model.home.rpy(i) - degToRad(request.tilt_deg);
    box.hi(3 + i) = model.home.rpy(i) + degToRad(request.tilt_deg);
  }
  simulation::RandomStream rng(request.seed, "plan-poses");
  const auto commands = simulation::sampleHexapodWorkspace(model, box, request.candidates, rng);
  std::vector<kinematics::PoseRpy> pool;
  pool.reserve(commands.size());
  for (const Eigen::VectorXd& c : commands) {
    kinematics::PoseRpy p;
    p.position = c.head<3>();
    p.rpy = c.tail<3>();
    pool.push_back(p);
  }
  return pool;
}

PlanPosesResult planHexapodPoses(const PlanPosesRequest& request,
                                 const detail::PlanStages& stages) {
  if (!request.target_offset.empty())
    throw InvalidArgument("--target-offset applies to Exechon machines only");
  io::HalReadOptions hal;
  if (!request.ini.empty()) hal.ini_path = request.ini;
  const io::HexapodMachine machine =
      request.hexapod ? *request.hexapod : io::loadHexapodMachine(request.machine, hal);
  if (!request.hexapod) stages.control().note(machine.notices);
  const kinematics::HexapodModel& model = machine.model;
  PKM_CHECK(request.tilt_deg >= 0.0 && request.reach >= 0.0, "--reach and --tilt must be >= 0");
  detail::checkProgram(request);
  stages.enter(1, "candidates", fmt::format("sampling {} candidates", request.candidates));
  const std::vector<kinematics::PoseRpy> pool = hexapodCandidates(model, request);
  cal::PosePlanOptions options;
  options.count = request.count;
  options.index = cal::parseObservabilityIndex(request.index);
  options.measurement = request.measurement == "point" ? cal::PlannedMeasurement::kPoint
                                                       : cal::PlannedMeasurement::kFullPose;
  stages.enter(2, "plan", fmt::format("choosing {} of {} poses", request.count, pool.size()));
  PlanPosesResult result;
  io::PosePlanReport& r = result.report;
  r.plan = cal::planHexapodPoses(model, pool, options);
  r.kind = "hexapod";
  r.machine = model.name;
  r.unit = model.unit;
  r.index_label = request.index;
  r.index = options.index;
  r.candidates = pool.size();
  r.parameters = cal::kHexapodParameters;
  r.feed = request.feed.value_or(detail::kDefaultFeed);
  r.home = model.home;
  for (int k : r.plan.chosen) r.poses.push_back(pool[static_cast<std::size_t>(k)]);
  detail::finishPlan(request, stages, result);
  return result;
}

}  // namespace

PlanPosesResult planPoses(const PlanPosesRequest& request, const RunControl& control) {
  request.validate();
  const detail::PlanStages stages(control);
  if (request.machineType() == "exechon") return detail::planExechonPoses(request, stages);
  return planHexapodPoses(request, stages);
}

}  // namespace pkm::workflow
