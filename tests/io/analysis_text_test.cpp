// io::analysisText: the tables of `pkm analyze` without --json, exactly.
#include "pkm/io/analysis_text.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace pkm::io {
namespace PKM_TEST_NS {

TEST(AnalysisTextTest, StraightnessTableWithSixDigitsAndContacts) {
  StraightnessReport r;
  r.reference = metrology::StraightnessReference::kMinimumZone;
  r.position = {0.0, 1.0, 2.0};
  r.deviation = {0.0, 1.0, 0.0};
  r.result.line = {0.0, 0.5};
  r.result.straightness = 1.0 / 3.0;
  r.result.residuals = {-0.5, 0.5, -0.5};
  r.result.contact_points = {1};
  EXPECT_EQ(analysisText(r),
            "straightness (minzone reference line, 3 points)\n"
            "slope\t0\nintercept\t0.5\nstraightness\t0.333333\n"
            "contact\t1\t0.5\n");
}

TEST(AnalysisTextTest, NonFiniteNumbersPrintAsDash) {
  SquarenessReport r;
  r.result.squareness = std::nan("");
  r.result.residual_rms = 1e-4;
  r.result.points_used = 7;
  r.diagonals = 2;
  EXPECT_EQ(analysisText(r),
            "face-diagonal squareness (2 diagonals, 7 readings, 0 PDGE tables)\n"
            "squareness\t- rad\nresidual_rms\t0.0001\n");
}

TEST(AnalysisTextTest, ComparisonLinesComeBeforeTheShiftedTable) {
  DiagonalsReport r;
  r.method = DiagonalMethod::kShifted;
  r.shifted = metrology::ShiftedDiagonalResult{};
  r.compare.push_back({"x.csv", "linear", {}});
  r.compare[0].comparison.positions = {0.0, 1.0};
  r.compare[0].comparison.rms = 0.5;
  const std::string t = analysisText(r);
  EXPECT_EQ(
      t.rfind("# compare,file,quantity,points,rms_mm,max_abs_mm\n# compare,x.csv,linear,2,0.5,0\n"
              "component,value_mm\n",
              0),
      0u);
  EXPECT_NE(t.find("# scale_z,0\n"), std::string::npos);
}

TEST(AnalysisTextTest, CircleContactsNameTheirSource) {
  CircleReport r;
  r.sources.beginInput("ring.csv");
  r.sources.addLine(2);
  r.sources.addLine(3);
  r.mzc.contacts[0] = {1, true, metrology::Point2(1.0, 2.0)};
  const std::string t = analysisText(r);
  EXPECT_EQ(t.rfind("circle (2 points)\n", 0), 0u);
  EXPECT_NE(t.find("MZC contact\touter\t1\t2\tring.csv:3\n"), std::string::npos);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
