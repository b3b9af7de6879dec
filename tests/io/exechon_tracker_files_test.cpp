#include "pkm/io/exechon_tracker_files.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "pkm/core/error.hpp"
#include "pkm/io/machine_loader.hpp"
#include "support/tolerances.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

class ExechonTrackerFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("pkm_exechon_tracker_" +
            std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const std::string p = (dir_ / name).string();
    std::ofstream(p) << text;
    return p;
  }
  std::filesystem::path dir_;
};

TEST_F(ExechonTrackerFiles, SimulatedFileRoundTrips) {
  const kinematics::ExechonModel m = loadExechonMachine("mxt700s-like").model;
  simulation::ExechonTrackerSetup s;
  s.name = "fit";
  s.count = 5;
  s.box_min = Eigen::Vector3d(-100, -100, 0);
  s.box_max = Eigen::Vector3d(100, 100, 100);
  s.smr_offset = Eigen::Vector3d(40, 0, 0);
  s.world_T_tracker.translation() = Eigen::Vector3d(1000, 0, 0);
  simulation::RandomStream rng(test::kSeed);
  const auto readings = simulation::simulateExechonTracker(m, m, {}, s, rng);
  const std::string text =
      exechonTrackerCsv(exechonTrackerMetadata("sc", 3, s, readings.size()), readings);
  EXPECT_THAT(text, HasSubstr("# smr offset mm: (40, 0, 0)\n"));
  EXPECT_THAT(text, HasSubstr("\nq1,q2,q3,c,a,x,y,z\n"));
  ExechonCalibrationInput in;
  const std::string path = write("fit.csv", text);
  addExechonCalibrationFile(path, in);
  ASSERT_EQ(in.data.observations.size(), readings.size());
  EXPECT_TRUE(in.tracker_frame);
  ASSERT_TRUE(in.target_offset.has_value());
  EXPECT_EQ(*in.target_offset, s.smr_offset);
  for (std::size_t k = 0; k < readings.size(); ++k) {
    const auto& o = in.data.observations[k];
    EXPECT_EQ(o.joints.readings, readings[k].joints.readings);  // full precision
    EXPECT_NEAR(o.joints.c, readings[k].joints.c, test::kTolExact);
    EXPECT_NEAR(o.joints.a, readings[k].joints.a, test::kTolExact);
    EXPECT_EQ(o.point, readings[k].measured);
    EXPECT_FALSE(o.direction.has_value());
  }
  EXPECT_EQ(in.data.observations[2].source, path + ":15");
}

TEST_F(ExechonTrackerFiles, LegsAreQ1ToQ3OrQ0ToQ2InOlderFiles) {
  ExechonCalibrationInput in;
  addExechonCalibrationFile(write("new.csv", "q1,q2,q3,c,a,x,y,z\n1,2,3,0,90,4,5,6\n"), in);
  addExechonCalibrationFile(write("old.csv", "q0,q1,q2,c,a,x,y,z\n1,2,3,0,90,4,5,6\n"), in);
  ASSERT_EQ(in.data.observations.size(), 2u);
  EXPECT_EQ(in.data.observations[0].joints.readings, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(in.data.observations[1].joints.readings, Eigen::Vector3d(1, 2, 3));
}

TEST_F(ExechonTrackerFiles, DirectionsAndErrors) {
  ExechonCalibrationInput in;
  addExechonCalibrationFile(write("d.csv", "q0,q1,q2,c,a,x,y,z,i,j,k\n1,2,3,0,90,4,5,6,0,0,-1\n"),
                            in);
  ASSERT_EQ(in.data.observations.size(), 1u);
  ASSERT_TRUE(in.data.observations[0].direction.has_value());
  EXPECT_EQ(*in.data.observations[0].direction, Eigen::Vector3d(0, 0, -1));
  EXPECT_NEAR(in.data.observations[0].joints.a, M_PI / 2, test::kTolExact);
  EXPECT_FALSE(in.tracker_frame);
  const auto fails = [&](const std::string& text, const std::string& what) {
    ExechonCalibrationInput x;
    try {
      addExechonCalibrationFile(write("bad.csv", text), x);
      ADD_FAILURE() << "expected: " << what;
    } catch (const IoError& e) {
      EXPECT_THAT(e.what(), HasSubstr(what));
    }
  };
  fails("q0,q1,q2,c,a,x,y,z,i,j,k\n1,2,3,0,90,4,5,6,0,0,-2\n", "bad.csv:2: the tool direction");
  fails("q0,q1,q2,c,a,x,y,z,i,j\n1,2,3,0,90,4,5,6,0,0\n", "needs all of i, j, k");
  fails("q0,q1,q2,c,a,x,y\n1,2,3,0,90,4,5\n", "missing column 'z'");
  fails("q0,q1,q2,c,a,x,y,z\n1,2,3,0,nan?,4,5,6\n", "bad.csv:2:");
  // Two files that disagree on the target offset.
  ExechonCalibrationInput two;
  addExechonCalibrationFile(
      write("a.csv", "# smr offset mm: (40, 0, 0)\nq0,q1,q2,c,a,x,y,z\n1,2,3,0,0,4,5,6\n"), two);
  EXPECT_THROW(
      addExechonCalibrationFile(
          write("b.csv", "# smr offset mm: (0, 40, 0)\nq0,q1,q2,c,a,x,y,z\n1,2,3,0,0,4,5,6\n"),
          two),
      IoError);
}

TEST_F(ExechonTrackerFiles, HybridFilesRoundTrip) {
  simulation::HybridTrackerSetup s;
  s.name = "h";
  s.count = 3;
  s.smr_offset = Eigen::Vector3d(0, 0, 40);
  std::vector<simulation::HybridTrackerReading> readings(2);
  readings[0].command.x2 = 100.25;
  readings[0].command.pkm = Eigen::Vector3d(1, 2, 3);
  readings[0].measured = Eigen::Vector3d(4, 5, 6);
  readings[1].command.y2 = 0.1;
  readings[1].measured = Eigen::Vector3d(7, 8, 9.5);
  const std::string text = hybridTrackerCsv(hybridTrackerMetadata("sc", 1, s, 2), readings);
  EXPECT_THAT(text, HasSubstr("\nx2,y2,xp,yp,zp,x,y,z\n"));
  ExechonCalibrationInput in;
  addExechonCalibrationFile(write("h.csv", text), in);
  EXPECT_TRUE(in.data.observations.empty());
  ASSERT_EQ(in.hybrid.observations.size(), 2u);
  EXPECT_TRUE(in.hybrid.measurement_frame.has_value());
  EXPECT_EQ(in.hybrid.target_offset, s.smr_offset);
  EXPECT_EQ(in.hybrid.observations[0].command.x2, 100.25);
  EXPECT_EQ(in.hybrid.observations[0].command.pkm, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(in.hybrid.observations[1].point, Eigen::Vector3d(7, 8, 9.5));
  ExechonCalibrationInput bad;
  EXPECT_THROW(addExechonCalibrationFile(write("b.csv", "x2,y2,xp,yp,x,y,z\n1,2,3,4,5,6,7\n"), bad),
               IoError);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
