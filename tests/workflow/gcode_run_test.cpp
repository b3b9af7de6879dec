// workflow::runGcode: a short program's motions, points and checks on a hexapod, a violation
// found at its line, errors named after an upload, bad requests refused, the report file written
// and never over an existing one without force, progress and cancellation.
#include "pkm/workflow/gcode_run.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "pkm/cnc/exechon_path.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/machine_loader.hpp"
#include "support/scratch_files.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

using test::slurp;

fs::path scratch(const std::string& name) { return test::scratchPath("workflow_gcode_run", name); }

GcodeRunRequest request(std::string text, std::string machine = "hexapod-default") {
  GcodeRunRequest r;
  r.program = {"upload.ngc", std::move(text)};
  r.interpreter.require_program_end = false;  // snippets; the CLI tests check the end
  r.machine = std::move(machine);
  return r;
}

const io::GcodeCheckSummary& check(const io::GcodeRunReport& r, const std::string& name) {
  for (const io::GcodeCheckSummary& c : r.checks)
    if (c.name == name) return c;
  throw std::runtime_error("no check " + name);
}

TEST(GcodeRunWorkflow, AShortProgramPassesEveryCheck) {
  const GcodeRunResult r = runGcode(request("G0 X0 Y0 Z200\nG1 X10 F600\nG1 X20\nM2\n"));
  const io::GcodeRunReport& rep = r.report;
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(rep.program, "upload.ngc");
  EXPECT_EQ(rep.machine_type, "hexapod");
  EXPECT_EQ(rep.lines, 4u);
  EXPECT_EQ(rep.motions, 3u);
  EXPECT_GE(rep.points, rep.motions);
  EXPECT_EQ(rep.checks.size(), 8u);
  EXPECT_EQ(check(rep, "stroke").violations, 0u);
  EXPECT_TRUE(check(rep, "stroke").enabled);
  EXPECT_GT(rep.cycle_time_s, 0.0);
  EXPECT_EQ(rep.max_joint_velocity, 200.0);  // the built-in machine has no joint_rates
  EXPECT_EQ(rep.tolerance_mm, 0.01);
}

TEST(GcodeRunWorkflow, ARotaryOnlyMoveTakesAsLongUnderG20AsUnderG21) {
  // F300 on a rotary-only move is 300 deg/min under G20 too (LinuxCNC's feed rule): 15 deg take
  // at least 3 s, and the inch program times exactly as its millimetre twin.
  const GcodeRunResult mm = runGcode(request("G21 G0 X0 Y0 Z200\nG1 A15 F300\nM2\n"));
  const GcodeRunResult in = runGcode(request("G20 G0 X0 Y0 Z[200/25.4]\nG1 A15 F300\nM2\n"));
  EXPECT_TRUE(in.ok());
  EXPECT_EQ(check(in.report, "joint_velocity").violations, 0u);
  EXPECT_GE(in.report.cycle_time_s, 15.0 / 300.0 * 60.0);
  constexpr double kSameTime = 1e-9;  // s: the same path, up to the rounding of Z
  EXPECT_NEAR(in.report.cycle_time_s, mm.report.cycle_time_s, kSameTime);
}

TEST(GcodeRunWorkflow, TheExechonsAEqualsCEqualsZeroConvention) {
  // docs/conventions.md "A = C = 0 on an Exechon": with --orientation vector (the default) A = C
  // = 0 is a vertical tool; with --orientation axes (the wrist readings, what LinuxCNC's
  // pkmexechonkins reads) it is the tool along the tripod axis, which mxt700s-like's rpy_deg
  // (200, 0, 0) tilts 20 deg from the vertical about x; a vertical tool there needs A of about -20
  // deg.
  const io::ExechonMachine machine = io::loadExechonMachine("mxt700s-like");
  const cnc::Axes home{0.0, 68.404, 12.061, 0.0, 0.0, 0.0};  // the home tool point, mm
  const Eigen::Vector3d down(0.0, 0.0, -1.0);
  constexpr double kAngleTol = 0.01;  // deg: the home point is rounded to the micrometre
  cnc::ExechonJointConverter vector(machine.model, cnc::ExechonOrientation::kToolVector);
  const cnc::ExechonPathSample v = vector.solve(home);
  ASSERT_TRUE(v.ok());
  EXPECT_NEAR(
      pkm::radToDeg(std::acos(std::clamp(v.direction.dot(down), -1.0, 1.0))), 0.0, kAngleTol);
  cnc::ExechonJointConverter axes(machine.model, cnc::ExechonOrientation::kWristAxes);
  const cnc::ExechonPathSample w = axes.solve(home);
  ASSERT_TRUE(w.ok());
  EXPECT_NEAR(
      pkm::radToDeg(std::acos(std::clamp(w.direction.dot(down), -1.0, 1.0))), 20.0, kAngleTol);
  EXPECT_NEAR(w.direction.x(), 0.0, 1e-3);  // tilted about x only
  // The vertical tool's wrist A: about -20 deg, -23.10 here (the platform tilts a further 3 deg
  // when the wrist point S moves to keep the tool point).
  EXPECT_NEAR(v.joints(4), -23.102, kAngleTol);
}

TEST(GcodeRunWorkflow, AStrokeViolationIsFoundAtItsLine) {
  GcodeRunRequest q = request("G0 X0 Y0 Z200\nG1 Z100 F600\nG1 Z-300\n");
  q.max_joint_velocity = 150.0;
  const GcodeRunResult r = runGcode(q);
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(r.report.max_joint_velocity, 150.0);
  const io::GcodeCheckSummary& stroke = check(r.report, "stroke");
  EXPECT_GT(stroke.violations, 0u);
  EXPECT_EQ(stroke.first.line, 3u);
  EXPECT_LT(stroke.first.margin, 0.0);
}

TEST(GcodeRunWorkflow, ThePathAndEveryViolationForAFrontEnd) {
  GcodeRunRequest q = request("G0 X0 Y0 Z200\nG1 Z100 F600\nG1 Z-300\nG1 X50 Z200\nM2\n");
  const GcodeRunResult full = runGcode(q);
  EXPECT_TRUE(full.path.t.empty());  // not asked for
  EXPECT_TRUE(full.violations.empty());
  q.path_points = 1'000'000;
  q.max_violations = 1'000'000;
  const GcodeRunResult all = runGcode(q);
  ASSERT_EQ(all.path.total_points, all.report.points);
  ASSERT_EQ(all.path.t.size(), all.report.points);  // nothing decimated
  EXPECT_EQ(all.path.joints.size(), 6u);
  EXPECT_EQ(all.path.joint_units[0], "mm");
  EXPECT_EQ(all.path.q[0].size(), 6u);
  EXPECT_EQ(all.path.t.back(), all.report.cycle_time_s);  // no final dwell here
  std::size_t violated = 0;
  for (const io::GcodeCheckSummary& c : all.report.checks) violated += c.violations;
  ASSERT_EQ(all.violations.size(), violated);
  EXPECT_EQ(all.violations.front().check, "stroke");
  EXPECT_EQ(all.violations.front().event.line, check(all.report, "stroke").first.line);
  EXPECT_EQ(all.violations.front().event.unit, "mm");
  // Decimated to 20 points: the ends and each check's worst point stay, times increase.
  q.path_points = 20;
  q.max_violations = 2;
  const GcodeRunResult few = runGcode(q);
  EXPECT_LE(few.path.index.size(), 20u + 2 * all.report.checks.size());
  EXPECT_LT(few.path.index.size(), all.path.index.size());
  EXPECT_EQ(few.path.index.front(), 0u);
  EXPECT_EQ(few.path.index.back(), all.report.points - 1);
  EXPECT_TRUE(std::is_sorted(few.path.t.begin(), few.path.t.end()));
  const auto& worst = check(few.report, "stroke").worst.position;
  EXPECT_NE(std::find(few.path.pose.begin(), few.path.pose.end(), worst), few.path.pose.end());
  EXPECT_EQ(few.report.checks[0].violations, all.report.checks[0].violations);  // exact checks
  EXPECT_LE(few.violations.size(), 2 * all.report.checks.size());
}

TEST(GcodeRunWorkflow, FramesDrawTheMachineAlongThePath) {
  GcodeRunRequest q = request("G0 X0 Y0 Z200\nG1 X30 F600\nG2 X0 Y30 I-30 J0\nM2\n");
  q.frames = 25;
  const GcodeRunResult r = runGcode(q);
  ASSERT_GE(r.frames.size(), 20u);
  ASSERT_LE(r.frames.size(), 25u);
  EXPECT_EQ(r.frame_t.front(), 0.0);
  EXPECT_TRUE(std::is_sorted(r.frame_t.begin(), r.frame_t.end()));
  EXPECT_EQ(r.frames[0].status, "ok");
  EXPECT_EQ(r.frames[0].moving_points.size(), 6u);
  EXPECT_NEAR(r.frames.back().tool_point[1], 30.0, 1e-6);  // the arc's end
  GcodeRunRequest e = request("G0 X0 Y0 Z0\nG1 X5 F300\nM2\n", "mxt700s-like");
  e.frames = 3;
  const GcodeRunResult er = runGcode(e);
  ASSERT_FALSE(er.frames.empty());
  EXPECT_EQ(er.frames[0].wrist_points.size(), er.frames[0].status == "ok" ? 1u : 0u);
}

TEST(GcodeRunWorkflow, AMachineLoadedByTheFrontEndIsUsedInsteadOfItsName) {
  const std::string program = "G0 X0 Y0 Z200\nG1 X10 F600\nG1 X20\nM2\n";
  const GcodeRunResult by_name = runGcode(request(program));
  GcodeRunRequest q = request(program, "no-such-machine");
  auto machine = std::make_shared<io::HexapodMachine>(io::loadHexapodMachine("hexapod-default"));
  q.hexapod = machine;
  const GcodeRunResult loaded = runGcode(q);
  EXPECT_EQ(io::gcodeRunJson(loaded.report), io::gcodeRunJson(by_name.report));
  // A changed geometry is what runs: a longer offset, a shorter reading.
  q.path_points = 10;
  const GcodeRunResult before = runGcode(q);
  machine->model.struts[0].length_offset += 5.0;
  const GcodeRunResult changed = runGcode(q);
  ASSERT_FALSE(changed.path.q.empty());
  EXPECT_NEAR(changed.path.q[0][0], before.path.q[0][0] - 5.0, 1e-9);
  q.exechon = std::make_shared<io::ExechonMachine>(io::loadExechonMachine("mxt700s-like"));
  EXPECT_THROW((void)runGcode(q), InvalidArgument);
  q.hexapod = nullptr;
  q.program = {"e.ngc", "G0 X0 Y0 Z0\nG1 X1 F100\nM2\n"};
  EXPECT_EQ(runGcode(q).report.machine_type, "exechon");
}

TEST(GcodeRunWorkflow, AProgramNeedingTooManyPointsIsRefusedAtItsLine) {
  // A legal helix of a hundred million turns: refused at once (bounded memory), naming the line,
  // the points it needs and the option that raises the limit.
  GcodeRunRequest q = request("G0 X10 Y0 Z200\nG2 X10 Y0 I-10 J0 P100000000 F600\nM2\n");
  try {
    (void)runGcode(q);
    FAIL() << "accepted a hundred million turns";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), StartsWith("upload.ngc:2: the path would need at least "));
    EXPECT_THAT(e.what(), HasSubstr("more than the limit of 10000000: raise it with --max-points"));
  }
  q.max_points = 0;
  EXPECT_THROW((void)runGcode(q), InvalidArgument);
}

TEST(GcodeRunWorkflow, MovesThatGoNowhereAreHarmless) {
  const GcodeRunResult a =
      runGcode(request("G0 X0 Y0 Z200\nG1 F150\nG1 X10\nG1 F600\nG4 P1\nG1\nM2\n"));
  const GcodeRunResult b = runGcode(request("G0 X0 Y0 Z200\nF150\nG1 X10\nF600\nG4 P1\nM2\n"));
  EXPECT_EQ(a.report.motions, b.report.motions + 3);  // the three zero-length moves
  EXPECT_EQ(a.report.points, b.report.points);
  EXPECT_TRUE(std::isfinite(a.report.cycle_time_s));
  EXPECT_DOUBLE_EQ(a.report.cycle_time_s, b.report.cycle_time_s);
  EXPECT_TRUE(a.ok());
}

TEST(GcodeRunWorkflow, ErrorsNameTheUploadAndItsLine) {
  try {
    (void)runGcode(request("G0 X0\nG1 X1 Q\n"));
    FAIL() << "accepted a bad word";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), StartsWith("upload.ngc:2:"));
  }
  try {
    (void)runGcode(request("G0 X0 Y0 Z50\nG1 X10 B5 F600\n", "mxt700s-like"));
    FAIL() << "accepted a B word on an Exechon";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), StartsWith("upload.ngc:2: B5"));
  }
  EXPECT_THROW((void)runGcode(request("(nothing)\nM2\n")), InvalidArgument);
}

TEST(GcodeRunWorkflow, RejectsBadRequests) {
  GcodeRunRequest q = request("G0 X0 Y0 Z200\n");
  q.tolerance = 0.0;  // not > 0
  EXPECT_THROW(q.validate(), InvalidArgument);
  q = request("G0 X0 Y0 Z200\n");
  q.max_joint_acceleration = -1.0;
  EXPECT_THROW((void)runGcode(q), InvalidArgument);
  q = request("G0 X0 Y0 Z200\n");
  q.orientation = "axes";  // a hexapod has no wrist
  EXPECT_THROW((void)runGcode(q), InvalidArgument);
  q = request("G0 X0 Y0 Z200\n");
  q.interpreter.tool_units = "furlong";
  EXPECT_THROW((void)runGcode(q), InvalidArgument);
}

TEST(GcodeRunWorkflow, WritesTheReportAndRefusesToOverwriteIt) {
  GcodeRunRequest q = request("G0 X0 Y0 Z200\nG1 X10 F600\nM2\n");
  q.report = scratch("report.json").string();
  q.out = scratch("joints.csv").string();
  fs::remove(q.report);
  fs::remove(q.out);
  const GcodeRunResult r = runGcode(q);
  EXPECT_EQ(slurp(q.report), io::gcodeRunJson(r.report));
  EXPECT_THAT(slurp(q.out), StartsWith("line,t,x,y,z,a,b,c,q0,q1,q2,q3,q4,q5\n"));
  std::ofstream(q.report) << "keep";
  EXPECT_THROW((void)runGcode(q), IoError);
  EXPECT_EQ(slurp(q.report), "keep");
  q.force = true;
  (void)runGcode(q);
  EXPECT_EQ(slurp(q.report), io::gcodeRunJson(r.report));
}

TEST(GcodeRunWorkflow, ReportsProgressAndStopsWhenCancelled) {
  // 20000 motions: progress every kGcodeProgressInterval motions or points of each stage.
  GcodeRunRequest q =
      request("G0 X0 Y0 Z200\no1 repeat [10000]\nG1 X1 F6000\nG1 X0\no1 endrepeat\nM2\n");
  q.report = scratch("cancelled.json").string();
  fs::remove(q.report);
  CancellationToken token;
  std::vector<ProgressEvent> events;
  RunControl control;
  control.cancel = &token;
  control.progress = [&](const ProgressEvent& e) {
    events.push_back(e);
    if (e.stage == "interpolating") token.cancel();
  };
  EXPECT_THROW((void)runGcode(q, control), Cancelled);
  ASSERT_GE(events.size(), 3u);
  EXPECT_EQ(events.front().message, "interpreting: 0 motions");
  EXPECT_EQ(events[1].message, "interpreting: 10000 motions");
  EXPECT_EQ(events.back().stage, "interpolating");
  EXPECT_EQ(events.back().index, 2u);
  EXPECT_EQ(events.back().count, 3u);
  EXPECT_FALSE(fs::exists(q.report));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
