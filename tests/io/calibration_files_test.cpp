#include "pkm/io/calibration_files.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "pkm/core/error.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

/// Calls addCalibrationFile on `file` and returns the IoError's message ("" when none).
std::string errorOf(const NamedText& file) {
  CalibrationInput input;
  try {
    addCalibrationFile(file, input);
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

TEST(CalibrationFiles, VectorListsParseAndRejectBadGroups) {
  const auto v = parseVectorList("(150, 0, 0), (-75, 129.9, 0.5)", "f.csv", "gauge points mm");
  ASSERT_EQ(v.size(), 2U);
  EXPECT_EQ(v[1], Eigen::Vector3d(-75.0, 129.9, 0.5));
  EXPECT_THROW((void)parseVectorList("(1, 2)", "f.csv", "k"), IoError);
  EXPECT_THROW((void)parseVectorList("(1, 2, x)", "f.csv", "k"), IoError);
  EXPECT_THROW((void)parseVectorList("(1, 2, 3", "f.csv", "k"), IoError);
}

TEST(CalibrationFiles, TrackerPointsFromAnUploadKeepItsNameAndLines) {
  const NamedText upload{"points.csv",
                         "# smr offset mm: (0, 0, 12.5)\n# frame: tracker\n"
                         "l0,l1,l2,l3,l4,l5,x,y,z\n"
                         "1,2,3,4,5,6,7,8,9\n"
                         "\n"
                         "1,2,3,4,5,6,7,8,10\n"};
  CalibrationInput input;
  addCalibrationFile(upload, input);
  EXPECT_EQ(input.data.points.size(), 2U);
  EXPECT_TRUE(input.data.poses.empty());
  EXPECT_EQ(input.point_origin, (std::vector<std::string>{"points.csv:4", "points.csv:6"}));
  ASSERT_TRUE(input.target_offset.has_value());
  EXPECT_EQ(*input.target_offset, Eigen::Vector3d(0.0, 0.0, 12.5));
  EXPECT_TRUE(input.tracker_frame);
  EXPECT_THAT(input.notes.at(0), HasSubstr("points.csv: 2 points"));
}

TEST(CalibrationFiles, DistancesFromTheFirstRowOrToAPivot) {
  CalibrationInput line;
  addCalibrationFile(
      NamedText{"line.csv", "l0,l1,l2,l3,l4,l5,distance\n1,1,1,1,1,1,0\n2,2,2,2,2,2,5\n"}, line);
  ASSERT_EQ(line.data.distances.size(), 1U);
  EXPECT_EQ(line.data.distances[0].distance, 5.0);
  EXPECT_EQ(line.distance_origin.at(0), "line.csv:3");
  EXPECT_TRUE(line.data.distances[0].readings_from.has_value());

  CalibrationInput bar;
  addCalibrationFile(NamedText{"bar.csv",
                               "# pivot mm: (1, 2, 3)\nl0,l1,l2,l3,l4,l5,distance\n"
                               "1,1,1,1,1,1,100\n"},
                     bar);
  ASSERT_EQ(bar.data.distances.size(), 1U);
  EXPECT_FALSE(bar.data.distances[0].readings_from.has_value());
  EXPECT_EQ(bar.data.distances[0].from_point, Eigen::Vector3d(1.0, 2.0, 3.0));

  EXPECT_THAT(errorOf({"z.csv", "l0,l1,l2,l3,l4,l5,distance\n1,1,1,1,1,1,3\n2,2,2,2,2,2,5\n"}),
              HasSubstr("z.csv:2: the first row of a line is its zero"));
}

TEST(CalibrationFiles, ConstrainedMotionFromText) {
  const std::string header =
      "# gauge points mm: (100, 0, 0), (0, 100, 0), (-100, 0, 0)\n"
      "station,x,y,z,a,b,c,l0,l1,l2,l3,l4,l5,g0,g1,g2,converged\n";
  const NamedText gauges{"gauges.csv",
                         header + "0,0,0,0,0,0,0,1,1,1,1,1,1,0,0,0,1\n" +
                             "1,1,0,0,0,0,0,1,1,1,1,1,1,0.1,0,0,1\n" +
                             "2,2,0,0,0,0,0,1,1,1,1,1,1,0.2,0,0,0\n"};
  int skipped = 0;
  const calibration::ConstrainedMotionData set = readConstrainedMotionCsv(gauges, &skipped);
  EXPECT_EQ(set.stations.size(), 1U);
  EXPECT_EQ(skipped, 1);
  EXPECT_EQ(set.gauge_points[1], Eigen::Vector3d(0.0, 100.0, 0.0));

  CalibrationInput input;
  addCalibrationFile(gauges, input);
  EXPECT_EQ(input.data.constrained.size(), 1U);
  EXPECT_THAT(input.notes.at(0), HasSubstr("gauges.csv: constrained motion, 1 stations"));

  EXPECT_THAT(errorOf({"nozero.csv", header + "1,1,0,0,0,0,0,1,1,1,1,1,1,0.1,0,0,1\n"}),
              HasSubstr("nozero.csv: no station 0"));
}

TEST(CalibrationFiles, ErrorsNameTheInputAndLine) {
  EXPECT_THAT(errorOf({"up.csv", "l0,l1,l2,l3,l4,l5,x,y,z\n1,2,3,4,5,6,7,8,nine\n"}),
              HasSubstr("up.csv:2:"));
  EXPECT_THAT(errorOf({"cols.csv", "l0,l1,l2,x,y,z\n1,2,3,7,8,9\n"}), HasSubstr("cols.csv"));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
