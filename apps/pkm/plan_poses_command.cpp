// `pkm plan-poses`: choose calibration poses by an observability index and write them as CSV and
// as a G-code program that drives the machine through them (workflow::planPoses,
// docs/calibration.md).
#include <memory>

#include "cli_common.hpp"
#include "pkm/workflow/plan_poses.hpp"

namespace pkm::cli {

void addPlanPosesCommand(CLI::App& app) {
  auto a = std::make_shared<workflow::PlanPosesRequest>();
  CLI::App* cmd = app.add_subcommand(
      "plan-poses",
      "choose calibration poses (hexapod or Exechon) maximising an observability index");
  addMachineOptions(*cmd, a->machine, a->ini);
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
  cmd->add_option("--feed",
                  a->feed,
                  "G-code feed rate, machine units per minute (default: 1000, or less so that no "
                  "joint exceeds its velocity limit)")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--gcode", a->gcode, "also write the plan as a G-code program");
  cmd->add_flag("--force", a->force, "overwrite an existing G-code file");
  cmd->callback([a] {
    CliRunControl run;
    const workflow::PlanPosesResult result = workflow::planPoses(*a, run.control());
    run.finish();
    writeTextOutput("", result.csv);
  });
}

}  // namespace pkm::cli
