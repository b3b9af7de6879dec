// Laser-tracker files: the pose-file header, a write/read round trip of pose and point files with
// metadata, unit-suffixed and reordered columns, and FILE:LINE errors for bad files.
#include "pkm/io/tracker_files.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/geometry/error_motion.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/pose_rpy.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace io = pkm::io;
namespace sim = pkm::simulation;
namespace geo = pkm::geometry;
using pkm::test::kTolExact;
using ::testing::HasSubstr;

constexpr int kRows = 5;

std::vector<sim::TrackerReading> readings() {
  std::vector<sim::TrackerReading> out;
  for (int j = 0; j < kRows; ++j) {
    sim::TrackerReading r;
    r.command = Eigen::VectorXd::Zero(6);
    for (Eigen::Index i = 0; i < 6; ++i)
      r.lengths[i] = 250.0 + 0.1234567891 * (j + 1) * static_cast<double>(i + 1);
    const Eigen::Vector3d rpy(0.01 * j, -0.02 * j, 2.6 - 0.05 * j);  // rad
    r.measured = pkm::kinematics::toRigidTransform(
        {Eigen::Vector3d(-1234.5678901 + j, 567.123456789, -150.0 / 7.0), rpy});
    r.truth = r.measured;
    out.push_back(r);
  }
  return out;
}

/// `what` thrown by parseTrackerCsv for `text`.
std::string errorOf(const std::string& text) {
  try {
    (void)io::parseTrackerCsv(text, "t.csv");
  } catch (const pkm::IoError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return {};
}

TEST(TrackerFiles, PoseFileRoundTripsExactly) {
  sim::TrackerSetup setup;
  setup.name = "tracker-pose";
  setup.noise = *sim::trackerNoise("laser-tracker");
  const auto in = readings();
  const io::Metadata md = io::trackerMetadata("s", 4, setup, in.size());
  const std::string text = io::trackerCsv(md, sim::TrackerMode::kPose, in);
  EXPECT_THAT(text, HasSubstr("\nl0,l1,l2,l3,l4,l5,x,y,z,a,b,c\n"));
  EXPECT_THAT(text, HasSubstr("# format: pkm.tracker-pose/1\n"));
  const io::TrackerFile f = io::parseTrackerCsv(text, "t.csv");
  EXPECT_EQ(f.metadata, md);
  EXPECT_EQ(f.mode, sim::TrackerMode::kPose);
  ASSERT_EQ(f.lengths.size(), in.size());
  for (std::size_t j = 0; j < in.size(); ++j) {
    EXPECT_TRUE(f.lengths[j] == in[j].lengths);                   // shortest round-trip form
    EXPECT_TRUE(f.positions[j] == in[j].measured.translation());  // exactly
    const Eigen::Matrix3d R = geo::rotationFromRpy(f.rpy[j]);     // degrees and back
    EXPECT_NEAR((R - in[j].measured.linear()).cwiseAbs().maxCoeff(), 0.0, kTolExact);
    EXPECT_EQ(f.lines[j], md.size() + 2 + j);
  }
}

TEST(TrackerFiles, PointFileRoundTrips) {
  sim::TrackerSetup setup;
  setup.mode = sim::TrackerMode::kPoint;
  const auto in = readings();
  const std::string text =
      io::trackerCsv(io::trackerMetadata("s", 1, setup, in.size()), sim::TrackerMode::kPoint, in);
  EXPECT_THAT(text, HasSubstr("\nl0,l1,l2,l3,l4,l5,x,y,z\n"));
  EXPECT_THAT(text, HasSubstr("# format: pkm.tracker-point/1\n"));
  const io::TrackerFile f = io::parseTrackerCsv(text, "t.csv");
  EXPECT_EQ(f.mode, sim::TrackerMode::kPoint);
  EXPECT_TRUE(f.rpy.empty());
  ASSERT_EQ(f.positions.size(), in.size());
  EXPECT_TRUE(f.positions[3] == in[3].measured.translation());
}

TEST(TrackerFiles, ColumnsInAnyOrderWithUnitSuffixes) {
  const io::TrackerFile f = io::parseTrackerCsv(
      "\xEF\xBB\xBF# a comment\r\nc_deg,x_mm,note,y,z,a,b,l5,l4,l3,l2,l1,l0_mm\r\n"
      "90,1,n,2,3,0,0,15,14,13,12,11,10\r\n\r\n",
      "t.csv");
  ASSERT_EQ(f.lengths.size(), 1U);
  EXPECT_EQ(f.lengths[0][0], 10.0);
  EXPECT_EQ(f.lengths[0][5], 15.0);
  EXPECT_EQ(f.positions[0], Eigen::Vector3d(1, 2, 3));
  EXPECT_DOUBLE_EQ(f.rpy[0][2], pkm::degToRad(90.0));
  EXPECT_EQ(f.lines[0], 3U);
}

TEST(TrackerFiles, BadFilesGiveFileAndLine) {
  const std::string header = "l0,l1,l2,l3,l4,l5,x,y,z,a,b,c\n";
  const std::string row = "1,2,3,4,5,6,7,8,9,10,11,12\n";
  EXPECT_THAT(errorOf("# x: 1\nl0,l1,l2,l3,l4,x,y,z\n"), HasSubstr("t.csv:2: missing column 'l5'"));
  EXPECT_THAT(errorOf("l0,l1,l2,l3,l4,l5,x,y,z,a,b\n"),
              HasSubstr("t.csv:1: a pose file needs all"));
  EXPECT_THAT(errorOf("l0,l1,l2,l3,l4,l5,x,y,z,x_mm\n"),
              HasSubstr("t.csv:1: column 'x' appears twice"));
  EXPECT_THAT(errorOf(header + row + "1,2,3,4,5,6,7,8,9,10,11\n"),
              HasSubstr("t.csv:3: expected 12 fields, found 11"));
  EXPECT_THAT(errorOf(header + row + row + "1,2,3,4,5,6,7,8,nan,10,11,12\n"),
              HasSubstr("t.csv:4: z 'nan' is not a finite number"));
  EXPECT_THAT(errorOf(header + "1,2,3,4,5,6,7,8,9,10,11,1e999\n"),
              HasSubstr("t.csv:2: c '1e999' is not a finite number"));
  EXPECT_THAT(errorOf("# only: metadata\n"), HasSubstr("t.csv:1: no header row"));
  EXPECT_THAT(errorOf(header), HasSubstr("t.csv:1: no data rows"));
  EXPECT_THROW((void)io::readTrackerCsv("/no/such/dir/t.csv"), pkm::IoError);
}

}  // namespace PKM_TEST_NS
