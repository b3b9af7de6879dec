// `pkm plan-poses` for an Exechon: tracker points chosen by an observability index among tool
// poses that the machine reaches within every limit (docs/calibration.md, "Pose planning").
#include <fmt/format.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "pkm/calibration/exechon_pose_planning.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/exechon_machine.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/kinematics/exechon_data.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"
#include "pkm/simulation/exechon_tracker.hpp"
#include "plan_poses.hpp"

namespace pkm::cli {

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
                                        const PlanArgs& a,
                                        const Eigen::Vector3d& target_offset) {
  kin::ExechonData data(model);
  kin::evaluateConfiguration(model, data, model.home);
  const double reach = a.reach > 0.0 ? a.reach : 0.3 * model.characteristicLength();
  simulation::ExechonTrackerSetup setup;
  setup.name = "plan-poses";
  setup.count = a.candidates;
  setup.box_min = data.world_p_tool - Eigen::Vector3d::Constant(reach);
  setup.box_max = data.world_p_tool + Eigen::Vector3d::Constant(reach);
  setup.direction = data.world_u_tool;
  setup.max_tilt = degToRad(a.tilt_deg);
  setup.smr_offset = target_offset;
  simulation::RandomStream rng(a.seed, "plan-poses");
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

}  // namespace

void runExechonPlan(const PlanArgs& a) {
  const io::ExechonMachine machine = io::loadExechonMachine(a.machine.spec);
  const kin::ExechonModel& model = machine.model;
  if (a.measurement == "pose")
    throw InvalidArgument(
        "--measurement pose: an Exechon plan is for tracker points (--measurement point)");
  PKM_CHECK(a.candidates >= a.count,
            "--candidates ({}) must be at least --count ({})",
            a.candidates,
            a.count);
  PKM_CHECK(a.tilt_deg >= 0.0 && a.tilt_deg <= 90.0 && a.reach >= 0.0,
            "--reach must be >= 0 and --tilt within [0, 90] degrees");
  if (!a.gcode.empty() && !a.force && std::filesystem::exists(a.gcode))
    throw IoError(fmt::format("{} exists; pass --force to overwrite it", a.gcode));
  const Eigen::Vector3d target_offset =
      a.target_offset.empty()
          ? Eigen::Vector3d::Zero()
          : Eigen::Vector3d(a.target_offset[0], a.target_offset[1], a.target_offset[2]);
  const std::vector<Candidate> pool = sampleCandidates(model, a, target_offset);
  std::vector<kin::ExechonConfiguration> configurations;
  for (const Candidate& c : pool) configurations.push_back(c.configuration);
  cal::ExechonPosePlanOptions options;
  options.count = a.count;
  options.index = cal::parseObservabilityIndex(a.index);
  options.target_offset = target_offset;
  const cal::PosePlan plan = cal::planExechonPoses(model, configurations, options);

  Output out;
  std::string& t = out.text();
  t += "pose,x,y,z,i,j,k\n";  // the input of `pkm exechon ik --poses`
  for (std::size_t k = 0; k < plan.chosen.size(); ++k) {
    const kin::ExechonToolPose& p = pool[static_cast<std::size_t>(plan.chosen[k])].pose;
    t += fmt::format("{}", k);
    for (const Eigen::Vector3d* v : {&p.position, &p.direction})
      for (int i = 0; i < 3; ++i) {
        t += ',';
        io::appendNumber(t, (*v)(i));
      }
    t += '\n';
  }
  fmt::print(stderr,
             "pkm: note: {} tracker points of {} candidates by {}: {} = {:.6g} (random choice "
             "{:.6g}), condition number {:.4g}, rank {} of {}, {} exchanges\n",
             plan.chosen.size(),
             pool.size(),
             a.index,
             cal::toString(options.index),
             plan.index_value,
             plan.random_baseline,
             plan.condition_number,
             plan.rank,
             cal::kExechonParameters,
             plan.swaps);
  if (a.gcode.empty()) return;
  // A, C are the wrist readings of the planned configuration (`gcode run --orientation axes`):
  // between two points the readings move linearly, so the wrist never swings through the pole.
  std::string g = fmt::format(
      "(pkm plan-poses: {} tracker points for {} by {}; measure at every M0)\n"
      "(A, C are the wrist readings: run with --orientation axes)\n",
      a.count,
      model.name,
      cal::toString(options.index));
  g += fmt::format("{} G90 (absolute)\n", model.unit == LengthUnit::kInch ? "G20" : "G21");
  kin::ExechonData data(model);
  const auto move = [&](const kin::ExechonConfiguration& c) {
    kin::evaluateConfiguration(model, data, c);
    const Eigen::Vector3d& p = data.world_p_tool;
    // Rounded to the 4 decimals written, + 0.0: no "-0.0000".
    const auto w = [](double v) { return std::round(v * 1e4) / 1e4 + 0.0; };
    return fmt::format("X{:.4f} Y{:.4f} Z{:.4f} A{:.4f} C{:.4f}",
                       w(p.x()),
                       w(p.y()),
                       w(p.z()),
                       w(radToDeg(c.a)),
                       w(radToDeg(c.c)));
  };
  g += fmt::format("G1 {} F{:.1f} (home)\n", move(model.home), a.feed);
  for (std::size_t k = 0; k < plan.chosen.size(); ++k) {
    g += fmt::format("N{} G1 {}\n",
                     (k + 1) * 10,
                     move(pool[static_cast<std::size_t>(plan.chosen[k])].configuration));
    g += fmt::format("M0 (measure point {})\n", k);
  }
  g += fmt::format("G1 {}\nM2\n", move(model.home));
  std::ofstream f(a.gcode, std::ios::binary | std::ios::trunc);
  if (!f) throw IoError(locate(a.gcode, 0, "cannot write the file"));
  f << g;
}

}  // namespace pkm::cli
