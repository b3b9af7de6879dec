// io::parseSpatialAnalyzerPoints: the layouts SpatialAnalyzer's ASCII point export writes (names
// Collection Group Target, Group Target, Target or none; spaces or commas; `//` comments) and the
// errors for layouts pkm does not read.
#include "pkm/io/spatial_analyzer.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "pkm/core/error.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

std::string errorOf(const std::string& text) {
  try {
    (void)parseSpatialAnalyzerPoints({"sa.txt", text});
  } catch (const IoError& e) {
    return e.what();
  }
  return "no error";
}

TEST(SpatialAnalyzerPoints, ReadsTheExampleExport) {
  const NamedText file =
      readNamedText(std::string(PKM_SOURCE_DIR) + "/tests/data/exports/spatialanalyzer-points.txt");
  const std::vector<SpatialAnalyzerPoint> p = parseSpatialAnalyzerPoints(file);
  ASSERT_EQ(p.size(), 3u);
  EXPECT_EQ(p[0].collection, "Tracker");
  EXPECT_EQ(p[0].group, "Nest1");
  EXPECT_EQ(p[0].target, "P1");
  EXPECT_EQ(p[2].position, Eigen::Vector3d(1551.08047, -42.50013, 40.91176));
  EXPECT_EQ(p[2].line, 6u);
}

TEST(SpatialAnalyzerPoints, EveryNameLayoutAndBothSeparators) {
  auto p = parseSpatialAnalyzerPoints({"a", "G, T7, 1, 2, 3\nG, T8, 4, 5, 6\n"});
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[1].collection, "");
  EXPECT_EQ(p[1].group, "G");
  EXPECT_EQ(p[1].target, "T8");
  EXPECT_EQ(p[1].position, Eigen::Vector3d(4, 5, 6));
  p = parseSpatialAnalyzerPoints({"b", "pose_003\t1.5\t-2\t3e2\r\n"});
  EXPECT_EQ(p[0].target, "pose_003");
  EXPECT_EQ(p[0].position, Eigen::Vector3d(1.5, -2, 300));
  p = parseSpatialAnalyzerPoints({"c", "Point,X,Y,Z\n\n1 2 3\n"});  // a header, no names
  EXPECT_EQ(p[0].target, "");
  EXPECT_EQ(p[0].line, 3u);
}

TEST(SpatialAnalyzerPoints, LayoutsItDoesNotReadAreErrorsAtTheirLine) {
  EXPECT_THAT(errorOf("C G T 1 2 3 0.01 0.02\n"),
              HasSubstr("sa.txt:1: 8 fields: pkm reads SpatialAnalyzer's Cartesian point export"));
  EXPECT_THAT(errorOf("G T 1 2 3\nT 4 5 6\n"), HasSubstr("sa.txt:2: 4 fields, but line 1 has 5"));
  EXPECT_THAT(errorOf("T 1 nan 3\n"), HasSubstr("sa.txt:1: Y 'nan' is not a finite number"));
  EXPECT_THAT(errorOf("T 1 2\n"), HasSubstr("sa.txt:1: X 'T' is not a finite number"));
  EXPECT_THAT(errorOf("1 2\n"), HasSubstr("sa.txt:1: 2 fields"));
  EXPECT_THAT(errorOf("// only comments\n"), HasSubstr("sa.txt: no points"));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
