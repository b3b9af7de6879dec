// `pkm plan-poses`: choose calibration poses by an observability index and write them as CSV and
// as a G-code program that drives the machine through them (docs/calibration.md).
#include <fmt/format.h>

#include <filesystem>
#include <fstream>

#include "cli_common.hpp"
#include "pkm/calibration/pose_planning.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/simulation/hexapod_workspace.hpp"
#include "plan_poses.hpp"

namespace pkm::cli {
namespace {

namespace cal = pkm::calibration;

void runPlan(const PlanArgs& a) {
  if (io::machineTypeOf(a.machine.spec) == "exechon") {
    runExechonPlan(a);
    return;
  }
  if (!a.target_offset.empty())
    throw InvalidArgument("--target-offset applies to Exechon machines only");
  const io::HexapodMachine machine = a.machine.load();
  const kinematics::HexapodModel& model = machine.model;
  PKM_CHECK(a.candidates >= a.count,
            "--candidates ({}) must be at least --count ({})",
            a.candidates,
            a.count);
  PKM_CHECK(a.tilt_deg >= 0.0 && a.reach >= 0.0, "--reach and --tilt must be >= 0");
  if (!a.gcode.empty() && !a.force && std::filesystem::exists(a.gcode))
    throw IoError(fmt::format("{} exists; pass --force to overwrite it", a.gcode));
  // Candidates: uniform in a box about home, kept where every limit holds.
  const double reach = a.reach > 0.0 ? a.reach : 0.4 * model.characteristicLength();
  simulation::PoseBox box;
  for (int i = 0; i < 3; ++i) {
    box.lo(i) = model.home.position(i) - reach;
    box.hi(i) = model.home.position(i) + reach;
    box.lo(3 + i) = model.home.rpy(i) - degToRad(a.tilt_deg);
    box.hi(3 + i) = model.home.rpy(i) + degToRad(a.tilt_deg);
  }
  simulation::RandomStream rng(a.seed, "plan-poses");
  const auto commands = simulation::sampleHexapodWorkspace(model, box, a.candidates, rng);
  std::vector<kinematics::PoseRpy> pool;
  for (const Eigen::VectorXd& c : commands) {
    kinematics::PoseRpy p;
    p.position = c.head<3>();
    p.rpy = c.tail<3>();
    pool.push_back(p);
  }
  cal::PosePlanOptions options;
  options.count = a.count;
  options.index = cal::parseObservabilityIndex(a.index);
  options.measurement = a.measurement == "point" ? cal::PlannedMeasurement::kPoint
                                                 : cal::PlannedMeasurement::kFullPose;  // "" too
  const cal::PosePlan plan = cal::planHexapodPoses(model, pool, options);

  Output out;
  std::string& t = out.text();
  t += "pose,x,y,z,a,b,c\n";
  for (std::size_t k = 0; k < plan.chosen.size(); ++k) {
    const kinematics::PoseRpy& p = pool[static_cast<std::size_t>(plan.chosen[k])];
    t += fmt::format("{}", k);
    for (int i = 0; i < 3; ++i) {
      t += ',';
      io::appendNumber(t, p.position(i));
    }
    for (int i = 0; i < 3; ++i) {
      t += ',';
      io::appendNumber(t, radToDeg(p.rpy(i)));
    }
    t += '\n';
  }
  fmt::print(stderr,
             "pkm: note: {} poses of {} candidates by {}: {} = {:.6g} (random choice {:.6g}), "
             "condition number {:.4g}, rank {}, {} exchanges\n",
             plan.chosen.size(),
             pool.size(),
             a.index,
             cal::toString(options.index),
             plan.index_value,
             plan.random_baseline,
             plan.condition_number,
             plan.rank,
             plan.swaps);
  if (a.gcode.empty()) return;
  std::string g =
      fmt::format("(pkm plan-poses: {} calibration poses for {} by {}; measure at every M0)\n",
                  a.count,
                  model.name,
                  cal::toString(options.index));
  g += fmt::format("{} G90 (absolute)\n", model.unit == LengthUnit::kInch ? "G20" : "G21");
  const kinematics::PoseRpy& home = model.home;
  g += fmt::format("G1 X{:.4f} Y{:.4f} Z{:.4f} A{:.4f} B{:.4f} C{:.4f} F{:.1f} (home)\n",
                   home.position.x(),
                   home.position.y(),
                   home.position.z(),
                   radToDeg(home.rpy.x()),
                   radToDeg(home.rpy.y()),
                   radToDeg(home.rpy.z()),
                   a.feed);
  for (std::size_t k = 0; k < plan.chosen.size(); ++k) {
    const kinematics::PoseRpy& p = pool[static_cast<std::size_t>(plan.chosen[k])];
    g += fmt::format("N{} G1 X{:.4f} Y{:.4f} Z{:.4f} A{:.4f} B{:.4f} C{:.4f}\n",
                     (k + 1) * 10,
                     p.position.x(),
                     p.position.y(),
                     p.position.z(),
                     radToDeg(p.rpy.x()),
                     radToDeg(p.rpy.y()),
                     radToDeg(p.rpy.z()));
    g += fmt::format("M0 (measure pose {})\n", k);
  }
  g += fmt::format("G1 X{:.4f} Y{:.4f} Z{:.4f} A{:.4f} B{:.4f} C{:.4f}\nM2\n",
                   home.position.x(),
                   home.position.y(),
                   home.position.z(),
                   radToDeg(home.rpy.x()),
                   radToDeg(home.rpy.y()),
                   radToDeg(home.rpy.z()));
  std::ofstream f(a.gcode, std::ios::binary | std::ios::trunc);
  if (!f) throw IoError(locate(a.gcode, 0, "cannot write the file"));
  f << g;
}

}  // namespace

void addPlanPosesCommand(CLI::App& app) {
  auto a = std::make_shared<PlanArgs>();
  CLI::App* cmd = app.add_subcommand(
      "plan-poses",
      "choose calibration poses (hexapod or Exechon) maximising an observability index");
  a->machine.add(*cmd);
  cmd->add_option("--count", a->count, "number of poses")->required()->check(CLI::Range(1, 100000));
  cmd->add_option("--index", a->index, "observability index O1..O5")
      ->check(CLI::IsMember({"O1", "O2", "O3", "O4", "O5", "o1", "o2", "o3", "o4", "o5"}));
  cmd->add_option("--measurement",
                  a->measurement,
                  "pose (6-DOF; the hexapod default) or point (SMR; the only one for an Exechon)")
      ->check(CLI::IsMember({"pose", "point"}));
  cmd->add_option("--candidates", a->candidates, "random workspace candidates to choose from")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--seed", a->seed, "random seed of the candidates");
  cmd->add_option("--reach",
                  a->reach,
                  "half-range of x, y, z about home (default 0.4 x the platform radius; Exechon: "
                  "0.3 x the largest base dimension)");
  cmd->add_option("--tilt",
                  a->tilt_deg,
                  "half-range of a, b, c about home, degrees (Exechon: the largest tilt of the "
                  "tool from its home direction)");
  cmd->add_option("--target-offset",
                  a->target_offset,
                  "Exechon: the tracker target in the tool frame x,y,z (default 0,0,0)")
      ->delimiter(',')
      ->expected(3);
  cmd->add_option("--feed", a->feed, "G-code feed rate, machine units per minute");
  cmd->add_option("--gcode", a->gcode, "also write the plan as a G-code program");
  cmd->add_flag("--force", a->force, "overwrite an existing G-code file");
  cmd->callback([a] { runPlan(*a); });
}

}  // namespace pkm::cli
