// workflow::analyzeIso230_2 / analyzeStraightness / analyzeParallelism / analyzeSquareness on small
// data with closed-form results; upload-named errors; bad requests refused.
#include "pkm/workflow/analyze_positioning.hpp"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pkm/core/error.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

TEST(AnalyzePositioningWorkflow, Iso230_2MeansAndReversalOfTwoRunsEachWay) {
  Iso230_2Request r;
  r.data = {{"upload.csv",
             "target,direction,run,measured\n"
             "0,+,1,0.001\n0,+,2,0.003\n0,-,1,0.000\n0,-,2,0.002\n"
             "10,+,1,10.001\n10,+,2,10.003\n10,-,1,10.000\n10,-,2,10.002\n"}};
  const io::Iso230_2Report rep = analyzeIso230_2(r);
  ASSERT_EQ(rep.result.targets.size(), 2u);
  EXPECT_NEAR(rep.result.targets[0].mean_up, 0.002, 1e-12);
  EXPECT_NEAR(rep.result.targets[0].mean_down, 0.001, 1e-12);
  EXPECT_NEAR(rep.result.B, 0.001, 1e-12);
  EXPECT_EQ(rep.coverage, 2.0);
}

TEST(AnalyzePositioningWorkflow, FilesWithoutAUnitOnAnInchMachineAreFlagged) {
  // Five runs each way at five targets (conforming), the header stating no unit.
  std::string text = "target,direction,run,measured\n";
  for (int run = 1; run <= 5; ++run)
    for (int t = 0; t <= 4; ++t)
      for (const char* d : {"+", "-"})
        text += fmt::format("{},{},{},{}\n", t * 2, d, run, t * 2 + 0.0001 * run);
  Iso230_2Request r;
  r.data = {{"laser.csv", text}};
  r.machine = "hexapod-linuxcnc-sim";  // an inch machine
  io::Iso230_2Report rep = analyzeIso230_2(r);
  ASSERT_EQ(rep.warnings.size(), 1u);
  EXPECT_THAT(rep.warnings[0], HasSubstr("laser.csv: its header states no length unit"));
  EXPECT_THAT(rep.warnings[0], HasSubstr("inches read as mm? Give --unit inch"));
  r.strict = true;
  EXPECT_THROW((void)analyzeIso230_2(r), InvalidArgument);
  r.columns.unit = "in";  // stated: converted, no warning
  rep = analyzeIso230_2(r);
  EXPECT_TRUE(rep.warnings.empty());
  EXPECT_NEAR(rep.result.targets[1].target, 2 * 25.4, 1e-9);
  r.columns.unit.clear();
  r.machine = "hexapod-default";  // a millimetre machine: mm is right
  EXPECT_TRUE(analyzeIso230_2(r).warnings.empty());
}

TEST(AnalyzePositioningWorkflow, AnUploadsErrorNamesTheUploadAndLine) {
  Iso230_2Request r;
  r.data = {{"my upload", "target,direction,run,measured\n0,+,0,0.1\n"}};
  try {
    (void)analyzeIso230_2(r);
    FAIL() << "accepted run 0";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("my upload:2: run must be >= 1"));
  }
}

TEST(AnalyzePositioningWorkflow, BadRequestsAreRefused) {
  Iso230_2Request r;
  EXPECT_THROW(r.validate(), IoError);  // no data
  r.data = {{"a", "target,direction,run,measured\n"}};
  r.coverage = 0.0;
  EXPECT_THROW((void)analyzeIso230_2(r), InvalidArgument);
  ParallelismRequest p;
  p.reference = p.axis = r.data;
  p.axis_sign = 0;
  EXPECT_THROW(p.validate(), InvalidArgument);
  SquarenessRequest s;
  s.data = r.data;
  s.pdge.push_back({2, 0, {"t", ""}});
  EXPECT_THROW(s.validate(), InvalidArgument);
}

TEST(AnalyzePositioningWorkflow, EndpointStraightnessOfATriangle) {
  StraightnessRequest r;
  r.data = {{"s.csv", "position,deviation\n0,0\n1,1\n2,0\n"}};
  r.reference = metrology::StraightnessReference::kEndpoint;
  const io::StraightnessReport rep = analyzeStraightness(r);
  EXPECT_NEAR(rep.result.line.slope, 0.0, 1e-15);
  EXPECT_NEAR(rep.result.straightness, 1.0, 1e-15);
  EXPECT_EQ(rep.position.size(), 3u);
}

TEST(AnalyzePositioningWorkflow, ParallelismIsTheSlopeDifference) {
  ParallelismRequest r;
  r.reference = {{"ref.csv", "position,deviation\n0,0\n100,0.001\n200,0.002\n"}};
  r.axis = {{"axis.csv", "position,deviation\n0,0\n100,0.003\n200,0.006\n"}};
  r.plane = io::ParallelismPlane::kVertical;
  const io::ParallelismReport rep = analyzeParallelism(r);
  EXPECT_NEAR(rep.result.reference_slope, 1e-5, 1e-15);
  EXPECT_NEAR(rep.result.axis_slope, 3e-5, 1e-15);
  ASSERT_TRUE(rep.sxP.has_value());
  EXPECT_FALSE(rep.szP.has_value());
  EXPECT_EQ(rep.axis_position.size(), 3u);
}

TEST(AnalyzePositioningWorkflow, SquarenessOfOneFaceDiagonal) {
  // A squareness xy shortens the diagonal (u, v) by xy·u·v/√(u² + v²) (docs/conventions.md,
  // "First-order diagonal formula").
  const double s = 1e-4;
  std::string text = "u,v,deviation\n";
  for (int k = 0; k <= 4; ++k) {
    const double u = 25.0 * k;
    text += fmt::format("{},{},{}\n", u, u, k == 0 ? 0.0 : -s * u * u / std::hypot(u, u));
  }
  SquarenessRequest r;
  r.data = {{"diag", text}};
  const io::SquarenessReport rep = analyzeSquareness(r);
  EXPECT_EQ(rep.diagonals, 1u);
  EXPECT_EQ(rep.result.points_used, 4);
  EXPECT_NEAR(rep.result.squareness, s, 1e-12);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
