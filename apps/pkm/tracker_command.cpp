// `pkm tracker join --plan PLAN.csv --points EXPORT.txt [--machine M] [--out FILE]`: a measurement
// plan and a laser tracker's point export joined into a tracker point file for `pkm calibrate
// hexapod` (workflow::joinTrackerPoints, docs/linuxcnc.md).
#include <memory>

#include "cli_common.hpp"
#include "pkm/workflow/tracker_join.hpp"

namespace pkm::cli {
namespace {

struct JoinArgs {
  std::string plan, points;
  std::vector<double> smr_offset;
  workflow::TrackerJoinRequest request;
};

void runJoin(JoinArgs& a) {
  workflow::TrackerJoinRequest& q = a.request;
  if (!a.smr_offset.empty())
    q.smr_offset = Eigen::Vector3d(a.smr_offset[0], a.smr_offset[1], a.smr_offset[2]);
  q.validate();  // option errors before the files are read
  q.plan = {a.plan, io::readTextFile(a.plan)};
  q.points = {a.points, io::readTextFile(a.points)};
  const workflow::TrackerJoinResult r = workflow::joinTrackerPoints(q);
  printNotices(r.notes);
  if (q.out.empty()) writeTextOutput("", r.text);
}

void addTracker(CLI::App& app) {
  CLI::App* group = app.add_subcommand("tracker", "prepare laser-tracker data");
  group->require_subcommand(1);
  auto a = std::make_shared<JoinArgs>();
  workflow::TrackerJoinRequest& q = a->request;
  CLI::App* join = group->add_subcommand(
      "join",
      "join a measurement plan (pkm plan-poses CSV) and the tracker's point export "
      "(SpatialAnalyzer ASCII: [[Collection] Group] Target X Y Z, one point per pose, the target "
      "named after its pose: P7, pose_007) into a tracker point file for pkm calibrate hexapod");
  join->add_option("--plan", a->plan, "the plan: pose,x,y,z,a,b,c (pkm plan-poses)")->required();
  join->add_option("--points", a->points, "the tracker's point export")->required();
  addMachineOptions(*join, q.machine, q.ini);
  join->add_option("--unit", q.unit, "the export's length unit (default: the machine's)")
      ->check(CLI::IsMember({"mm", "um", "m", "in"}));
  join->add_option(
          "--smr-offset", a->smr_offset, "the target on the tool: x y z, tool frame, machine unit")
      ->expected(3);
  join->add_option("--frame",
                   q.frame,
                   "frame of the points: tracker (default; its placement is fitted) or world")
      ->check(CLI::IsMember({"tracker", "world"}));
  join->add_option("--out,-o", q.out, "write the tracker file to FILE instead of standard output");
  join->add_flag("--force", q.force, "overwrite an existing --out file");
  join->callback([a] { runJoin(*a); });
}

const CommandRegistration kRegisterTracker{105, "tracker", &addTracker};

}  // namespace
}  // namespace pkm::cli
