// `pkm tracker join`: a plan of `pkm plan-poses` and a SpatialAnalyzer export joined into a
// tracker point file that `pkm calibrate hexapod` reads; its notes, --out without overwrite, bad
// input as exit 2 naming the file and line.
#include <filesystem>
#include <string>

#include "support/cli_fixture.hpp"

namespace pkm::test {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

TEST_F(CliTest, TrackerJoinWritesATrackerPointFile) {
  const CliRun plan = pkm({"plan-poses", "--count", "3", "--measurement", "point"});
  ASSERT_EQ(plan.code, 0) << plan.err;
  const std::string plan_path = write("plan.csv", plan.out);
  const std::string sa = write("sa.txt",
                               "// SA Version: 2024.1\n"
                               "Tracker Poses P2 1510.1 -80.2 3.3\n"
                               "Tracker Poses P0 1500.1 -90.2 1.3\n");
  const std::vector<std::string> args{
      "tracker", "join", "--plan", plan_path, "--points", sa, "--smr-offset", "0", "60", "80"};
  const CliRun r = pkm(args);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("# format: pkm.tracker-point/1\n"));
  EXPECT_THAT(r.out, HasSubstr("# smr offset mm: (0, 60, 80)\n"));
  EXPECT_THAT(r.out, HasSubstr(",1500.1,-90.2,1.3\n"));  // pose 0 first, as planned
  EXPECT_THAT(r.err, HasSubstr("pose 1 (" + plan_path + ":3): no point in " + sa + "; left out"));
  std::vector<std::string> to_file = args;
  to_file.insert(to_file.end(), {"--out", path("joined.csv")});
  EXPECT_EQ(pkm(to_file).code, 0);
  EXPECT_EQ(slurp(path("joined.csv")), r.out);
  EXPECT_EQ(pkm(to_file).code, 2);  // exists: not overwritten without --force
  const CliRun bad =
      pkm({"tracker", "join", "--plan", plan_path, "--points", write("bad.txt", "P0 1 x 3\n")});
  EXPECT_EQ(bad.code, 2);
  EXPECT_THAT(bad.err, HasSubstr("bad.txt:1: Y 'x' is not a finite number"));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::test
