// `pkm plan-poses`: calibration pose plans for a hexapod (the plan, its G-code program within the
// joints' velocity limits, the same plan for the same seed) and for an Exechon (tracker points
// that identify all 26 parameters), tested by running the built binary (PKM_BINARY).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/cli_fixture.hpp"

namespace pkm::test {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

TEST_F(CliTest, PlanPosesWritesAPlanAndAProgram) {
  const CliRun r = pkm({"plan-poses",
                        "--machine",
                        "hexapod-default",
                        "--count",
                        "12",
                        "--index",
                        "O2",
                        "--candidates",
                        "200",
                        "--gcode",
                        path("plan.ngc")});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto lines = splitLines(r.out);
  ASSERT_EQ(lines.size(), 13u);
  EXPECT_EQ(lines[0], "pose,x,y,z,a,b,c");
  EXPECT_EQ(splitFields(lines[12]).size(), 7u);
  EXPECT_THAT(r.err, HasSubstr("rank 42"));
  const std::string program = slurp(path("plan.ngc"));
  EXPECT_THAT(program, HasSubstr("G21 G90"));
  EXPECT_EQ(splitLines(program).size(), 2u + 1u + 2u * 12u + 2u);
  // The same seed gives the same plan; an existing program is not overwritten.
  const CliRun again = pkm({"plan-poses",
                            "--machine",
                            "hexapod-default",
                            "--count",
                            "12",
                            "--index",
                            "O2",
                            "--candidates",
                            "200"});
  EXPECT_EQ(again.out, r.out);
  expectUsageError(pkm({"plan-poses",
                        "--machine",
                        "hexapod-default",
                        "--count",
                        "12",
                        "--candidates",
                        "200",
                        "--gcode",
                        path("plan.ngc")}),
                   "exists");
  expectUsageError(
      pkm({"plan-poses", "--machine", "hexapod-default", "--count", "50", "--candidates", "20"}),
      "--candidates");
}

TEST_F(CliTest, PlanPosesFeedsRespectTheJointVelocityLimits) {
  // LinuxCNC's sim hexapod (inches, 20 in/s per joint): F1000 under G20 drives a strut at 1.2
  // times its limit, so the program gets a lower feed, and `gcode run` of it passes.
  const CliRun plan = pkm({"plan-poses",
                           "--machine",
                           "hexapod-linuxcnc-sim",
                           "--count",
                           "10",
                           "--gcode",
                           path("plan.ngc")});
  ASSERT_EQ(plan.code, 0) << plan.err;
  const std::string program = slurp(path("plan.ngc"));
  EXPECT_THAT(program, HasSubstr("G20 G90"));
  EXPECT_THAT(program, ::testing::Not(HasSubstr("F1000.0")));
  const CliRun run = pkm({"gcode", "run", "--machine", "hexapod-linuxcnc-sim", path("plan.ngc")});
  EXPECT_EQ(run.code, 0) << run.out << run.err;
  // A feed given explicitly is kept, with a notice naming a feed that fits.
  const CliRun fast = pkm({"plan-poses",
                           "--machine",
                           "hexapod-linuxcnc-sim",
                           "--count",
                           "10",
                           "--feed",
                           "1000",
                           "--gcode",
                           path("fast.ngc")});
  ASSERT_EQ(fast.code, 0) << fast.err;
  EXPECT_THAT(fast.err, HasSubstr("--feed 1000: a joint would move at"));
  EXPECT_THAT(slurp(path("fast.ngc")), HasSubstr("F1000.0"));
}

/// An Exechon plan: tracker points (tool point and direction) that identify all 26 parameters,
/// a program in wrist-axes form that `gcode run` passes, and the CSV `exechon ik` reads.
TEST_F(CliTest, PlanPosesForAnExechon) {
  const std::vector<std::string> args{"plan-poses",
                                      "--machine",
                                      "mxt700s-like",
                                      "--count",
                                      "30",
                                      "--candidates",
                                      "300",
                                      "--tilt",
                                      "30",
                                      "--target-offset",
                                      "40,0,0"};
  std::vector<std::string> with_gcode = args;
  with_gcode.insert(with_gcode.end(), {"--gcode", path("plan.ngc")});
  const CliRun r = pkm(with_gcode);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto lines = splitLines(r.out);
  ASSERT_EQ(lines.size(), 31u);
  EXPECT_EQ(lines[0], "pose,x,y,z,i,j,k");
  EXPECT_EQ(splitFields(lines[30]).size(), 7u);
  EXPECT_THAT(r.err, HasSubstr("rank 26 of 26"));
  const std::string program = slurp(path("plan.ngc"));
  EXPECT_THAT(program, HasSubstr("--orientation axes"));
  EXPECT_EQ(splitLines(program).size(), 3u + 1u + 2u * 30u + 2u);
  const CliRun run =
      pkm({"gcode", "run", "--machine", "mxt700s-like", "--orientation", "axes", path("plan.ngc")});
  EXPECT_EQ(run.code, 0) << run.out << run.err;
  // The plan's points are tool poses the IK solves (the CSV minus its pose column).
  std::string poses = "x,y,z,i,j,k\n";
  for (std::size_t k = 1; k < lines.size(); ++k)
    poses += lines[k].substr(lines[k].find(',') + 1) + "\n";
  const CliRun ik =
      pkm({"exechon", "ik", "--machine", "mxt700s-like", "--poses", write("p.csv", poses)});
  EXPECT_EQ(ik.code, 0) << ik.err;
  EXPECT_EQ(pkm(args).out, r.out);  // deterministic
  std::vector<std::string> pose = args;
  pose.insert(pose.end(), {"--measurement", "pose"});
  expectUsageError(pkm(pose), "tracker points");
  expectUsageError(pkm({"plan-poses", "--count", "3", "--target-offset", "1,2,3"}),
                   "Exechon machines only");
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::test