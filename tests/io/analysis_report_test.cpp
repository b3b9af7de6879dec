// io::analysisJson: the documents of `pkm analyze --json` from typed reports: members in their
// fixed order, settings echoed, optional members only when set, non-finite numbers as null.
#include "pkm/io/analysis_report.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

namespace pkm::io {
namespace PKM_TEST_NS {

using Json = nlohmann::ordered_json;

TEST(AnalysisReportTest, Iso230_2DocumentHasTheSummaryThenTheTargets) {
  Iso230_2Report r;
  r.coverage = 3.0;
  r.result.B = 0.25;
  r.result.E = std::nan("");
  r.result.targets.push_back({});
  r.result.targets[0].target = 10.0;
  r.result.targets[0].runs_up = 5;
  const std::string text = analysisJson(r);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  const Json j = Json::parse(text);
  EXPECT_EQ(j.begin().key(), "B");
  EXPECT_EQ(j["B"], 0.25);
  EXPECT_TRUE(j["E"].is_null());
  EXPECT_EQ(j["coverage_factor"], 3.0);
  EXPECT_EQ(j["targets"][0]["target"], 10.0);
  EXPECT_EQ(j["targets"][0]["runs_up"], 5);
}

TEST(AnalysisReportTest, ParallelismNamesTheSlopeDifferenceByPlane) {
  ParallelismReport r;
  r.plane = ParallelismPlane::kVertical;
  r.line = metrology::StraightnessReference::kEndpoint;
  r.result.slope_difference = 2e-5;
  r.result.deviations = {0.0, 1e-3};
  r.axis_position = {0.0, 100.0};
  r.sxP = 2e-5;
  const Json j = Json::parse(analysisJson(r));
  EXPECT_EQ(j["plane"], "vertical");
  EXPECT_EQ(j["line"], "endpoint");
  EXPECT_EQ(j["dalpha"], 2e-5);
  EXPECT_FALSE(j.contains("dgamma"));
  EXPECT_EQ(j["sxP"], 2e-5);
  EXPECT_FALSE(j.contains("szP"));
  EXPECT_EQ(j["deviations"][1], Json::array({100.0, 1e-3}));
}

TEST(AnalysisReportTest, DiagonalsDocumentCarriesOnlyItsMethodsResult) {
  DiagonalsReport r;
  r.method = DiagonalMethod::kShifted;
  r.size = Eigen::Vector3d(500, 400, 300);
  r.shifted = metrology::ShiftedDiagonalResult{};
  r.shifted->squareness = {1e-5, 2e-5, 3e-5};
  const Json j = Json::parse(analysisJson(r));
  EXPECT_EQ(j["method"], "shifted");
  EXPECT_EQ(j["size"], Json::array({500.0, 400.0, 300.0}));
  EXPECT_EQ(j["iso230_1"]["EB0Z"], -2e-5);
  EXPECT_TRUE(j.contains("travel_errors"));
  EXPECT_FALSE(j.contains("compare"));
  EXPECT_FALSE(j.contains("axes"));
}

TEST(AnalysisReportTest, ProbeOffsetReportsOProbeAsMinusTheOffset) {
  ProbeOffsetReport r;
  r.fit.offset = Eigen::Vector2d(0.01, -0.02);
  r.touches = 8;
  r.tool_plus_z = true;
  const Json j = Json::parse(analysisJson(r));
  EXPECT_EQ(j["o_probe"], Json::array({-0.01, 0.02}));
  EXPECT_EQ(j["tool_direction"], "+z");
  EXPECT_EQ(j["touches"], 8);
  EXPECT_FALSE(j.contains("eq9_o_probe"));
  EXPECT_STREQ(centreName(metrology::CircularCentre::kMinimumZone), "mzc");
}

TEST(PointSourcesTest, EachPointKnowsItsInputAndLine) {
  PointSources s;
  s.beginInput("a.csv");
  s.addLine(2);
  s.addLine(5);
  s.beginInput("empty.csv");  // an input without points
  s.beginInput("b.csv");
  s.addLine(3);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0].name, "a.csv");
  EXPECT_EQ(s[0].line, 2u);
  EXPECT_EQ(s[1].name, "a.csv");
  EXPECT_EQ(s[1].line, 5u);
  EXPECT_EQ(s[2].name, "b.csv");
  EXPECT_EQ(s[2].line, 3u);
}

TEST(PointSourcesTest, StartsEmpty) { EXPECT_EQ(PointSources().size(), 0u); }

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
