// workflow::planPoses: a small plan reaches full identifiability (hexapod 42, Exechon 26), the
// program is written only when allowed, a loaded machine plans as its name does, cancellation
// stops planning, bad requests are refused.
#include "pkm/workflow/plan_poses.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "pkm/core/error.hpp"
#include "pkm/io/machine_loader.hpp"
#include "support/scratch_files.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

fs::path scratch(const std::string& name) { return test::scratchPath("workflow_plan", name); }

using test::slurp;

PlanPosesRequest hexapodRequest() {
  PlanPosesRequest r;
  r.machine = "hexapod-default";
  r.count = 12;
  r.candidates = 200;
  return r;
}

TEST(PlanPosesWorkflow, AHexapodPlanIdentifiesAllParameters) {
  std::vector<std::string> notices;
  RunControl control;
  control.notice = [&](const std::string& n) { notices.push_back(n); };
  const PlanPosesResult r = planPoses(hexapodRequest(), control);
  EXPECT_EQ(r.report.kind, "hexapod");
  ASSERT_EQ(r.report.poses.size(), 12u);
  EXPECT_EQ(r.report.plan.rank, 42);  // every one of the 42 parameters is identifiable
  EXPECT_GT(r.report.plan.index_value, r.report.plan.random_baseline);
  EXPECT_EQ(r.report.candidates, 200u);
  EXPECT_THAT(r.csv, StartsWith("pose,x,y,z,a,b,c\n"));
  ASSERT_FALSE(notices.empty());
  EXPECT_EQ(notices.back(), r.summary);
  EXPECT_THAT(r.summary, HasSubstr("12 poses of 200 candidates by O1"));
  EXPECT_TRUE(r.gcode.empty());
  // Deterministic: the same seed gives the same plan.
  EXPECT_EQ(planPoses(hexapodRequest()).csv, r.csv);
}

TEST(PlanPosesWorkflow, AnExechonPlanIdentifiesAllParameters) {
  PlanPosesRequest q;
  q.machine = "mxt700s-like";
  q.count = 30;
  q.candidates = 300;
  q.tilt_deg = 30.0;
  q.target_offset = {40.0, 0.0, 0.0};
  const PlanPosesResult r = planPoses(q);
  EXPECT_EQ(r.report.kind, "exechon");
  ASSERT_EQ(r.report.points.size(), 30u);
  ASSERT_EQ(r.report.moves.size(), 31u);  // home and one per point
  EXPECT_EQ(r.report.plan.rank, 26);
  EXPECT_THAT(r.summary, HasSubstr("rank 26 of 26"));
  EXPECT_THAT(r.csv, StartsWith("pose,x,y,z,i,j,k\n"));
}

TEST(PlanPosesWorkflow, WritesTheProgramOnlyWhenAllowed) {
  const fs::path program = scratch("plan.ngc");
  fs::remove(program);
  PlanPosesRequest q = hexapodRequest();
  q.gcode = program.string();
  const PlanPosesResult r = planPoses(q);
  EXPECT_EQ(slurp(program), r.gcode);
  EXPECT_THAT(r.gcode, HasSubstr("G21 G90"));
  EXPECT_THAT(r.gcode, HasSubstr("M0 (measure pose 11)"));
  std::ofstream(program) << "keep";
  EXPECT_THROW((void)planPoses(q), IoError);
  EXPECT_EQ(slurp(program), "keep");
  q.force = true;
  EXPECT_EQ(planPoses(q).gcode, r.gcode);
  fs::remove(program);
}

TEST(PlanPosesWorkflow, ALoadedMachinePlansAsItsNameDoes) {
  const fs::path named_program = scratch("named.ngc"), loaded_program = scratch("loaded.ngc");
  fs::remove(named_program);
  fs::remove(loaded_program);
  PlanPosesRequest named = hexapodRequest();
  named.gcode = named_program.string();
  PlanPosesRequest loaded = hexapodRequest();
  loaded.machine = "no-such-machine";  // not read: the loaded machine is used
  loaded.hexapod =
      std::make_shared<const io::HexapodMachine>(io::loadHexapodMachine("hexapod-default"));
  loaded.gcode = loaded_program.string();
  const PlanPosesResult a = planPoses(named), b = planPoses(loaded);
  EXPECT_EQ(b.csv, a.csv);
  EXPECT_EQ(b.gcode, a.gcode);  // the feed checked on the loaded machine: the same
  PlanPosesRequest exechon;
  exechon.machine = "mxt700s-like";
  exechon.count = 8;
  exechon.candidates = 80;
  const std::string exechon_csv = planPoses(exechon).csv;
  exechon.machine = "default";  // a hexapod's name, ignored
  exechon.exechon =
      std::make_shared<const io::ExechonMachine>(io::loadExechonMachine("mxt700s-like"));
  EXPECT_EQ(exechon.machineType(), "exechon");
  EXPECT_EQ(planPoses(exechon).csv, exechon_csv);
  exechon.hexapod = loaded.hexapod;  // at most one loaded machine
  EXPECT_THROW(exechon.validate(), InvalidArgument);
  fs::remove(named_program);
  fs::remove(loaded_program);
}

TEST(PlanPosesWorkflow, CancellationStopsPlanning) {
  const fs::path program = scratch("cancelled.ngc");
  fs::remove(program);
  PlanPosesRequest q = hexapodRequest();
  q.gcode = program.string();
  CancellationToken token;
  std::vector<std::string> stages;
  RunControl control;
  control.cancel = &token;
  control.progress = [&](const ProgressEvent& e) {
    stages.push_back(e.stage);
    if (e.stage == "plan") token.cancel();
  };
  EXPECT_THROW((void)planPoses(q, control), Cancelled);
  EXPECT_EQ(stages, (std::vector<std::string>{"candidates", "plan"}));
  EXPECT_FALSE(fs::exists(program));
}

TEST(PlanPosesWorkflow, RefusesABadRequest) {
  PlanPosesRequest q = hexapodRequest();
  q.candidates = 5;
  EXPECT_THROW(q.validate(), InvalidArgument);
  try {
    (void)planPoses(q);
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("--candidates (5) must be at least --count (12)"));
  }
  q = hexapodRequest();
  q.index = "O9";
  EXPECT_THROW(q.validate(), InvalidArgument);
  q = hexapodRequest();
  q.target_offset = {1.0, 2.0, 3.0};
  EXPECT_THROW((void)planPoses(q), InvalidArgument);  // a hexapod has no target offset
  q = hexapodRequest();
  q.reach = -1.0;
  EXPECT_THROW((void)planPoses(q), InvalidArgument);
  q.machine = "mxt700s-like";
  q.reach = 0.0;
  q.measurement = "pose";  // an Exechon plan is for tracker points
  EXPECT_THROW((void)planPoses(q), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
