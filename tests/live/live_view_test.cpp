// A running LinuxCNC's record checked on its machine (pkm/live/live_view.hpp): the machine found
// from LinuxCNC's own hexapod-sim configuration, a record's joints compared with pkm's inverse
// kinematics (genhexkins' own strut lengths, 6 decimals), a strut past its limit flagged, the state
// word, and a configuration without genhexkins refused naming its INI.
#include "pkm/live/live_view.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "pkm/core/error.hpp"
#include "support/linuxcnc_record.hpp"
#include "support/linuxcnc_sample.hpp"

namespace pkm::live {
namespace PKM_TEST_NS {

using pkm::test::linuxcncRecord;
using ::testing::HasSubstr;

/// genhexkins' strut lengths of the hexapod-sim at x y z a b c = 2 -1 22 3 -4 10 (inch, degrees),
/// as LinuxCNC printed them (6 decimals).
const std::vector<double> kGenhexkins = {
    31.597194, 31.713899, 29.975223, 32.850082, 27.921167, 33.441616};
constexpr double kSixDecimals = 1e-6;  // LinuxCNC printed the lengths rounded to 6 decimals

class LiveViewTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ini_ = (pkm::test::linuxcncHexapodSim() / "hexapod.ini").string();
    if (!std::filesystem::exists(ini_)) GTEST_SKIP() << "no LinuxCNC sample at " << ini_;
  }
  static LinkSnapshot connected(const nlohmann::json& record) {
    LinkSnapshot s;
    s.connected = true;
    s.status = parseReaderLine(record.dump()).status;
    s.records = 1;
    return s;
  }
  std::string ini_;
};

TEST_F(LiveViewTest, TheMachineIsTheConfigurationsGenhexkinsFile) {
  const LiveMachine m = liveMachine(ini_);
  EXPECT_EQ(std::filesystem::path(m.hal).filename(), "kinematics.hal");
  EXPECT_EQ(m.units(), "inch");
  EXPECT_EQ(m.ini, ini_);
}

TEST_F(LiveViewTest, LinuxcncsJointsAgreeWithPkmsInverseKinematics) {
  const LiveFrame f = liveFrame(
      connected(linuxcncRecord(5, {2, -1, 22, 3, -4, 10}, kGenhexkins, ini_)), liveMachine(ini_));
  ASSERT_TRUE(f.pose_check.has_value());
  EXPECT_EQ(f.pose_check->status, "ok");
  EXPECT_LT(f.joint_disagreement, kSixDecimals);
  ASSERT_EQ(f.pose_check->joints.size(), 6u);
  EXPECT_EQ(f.pose_check->moving_points.size(), 6u);  // what the page draws
  EXPECT_EQ(f.state, "idle");
}

TEST_F(LiveViewTest, JointsThatDisagreeAreMeasured) {
  std::vector<double> off = kGenhexkins;
  off[3] += 0.01;
  const LiveFrame f =
      liveFrame(connected(linuxcncRecord(5, {2, -1, 22, 3, -4, 10}, off, ini_)), liveMachine(ini_));
  EXPECT_NEAR(f.joint_disagreement, 0.01, kSixDecimals);
}

TEST_F(LiveViewTest, AStrutBeyondItsLimitIsFlagged) {
  // A copy of the sample whose strut 3 may not extend past 30 in (it reads 32.85 at the pose).
  const auto dir = std::filesystem::temp_directory_path() / "pkm-live-view-limits";
  std::filesystem::remove_all(dir);
  std::filesystem::copy(pkm::test::linuxcncHexapodSim(), dir);
  std::ifstream in(dir / "hexapod.ini");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t joint3 = text.find("[JOINT_3]");
  const std::size_t limit = text.find("MAX_LIMIT = 1000.0", joint3);
  ASSERT_NE(limit, std::string::npos);
  text.replace(limit, 18, "MAX_LIMIT = 30.0");
  std::ofstream(dir / "hexapod.ini") << text;
  const LiveFrame f =
      liveFrame(connected(linuxcncRecord(5, {2, -1, 22, 3, -4, 10}, kGenhexkins, ini_)),
                liveMachine((dir / "hexapod.ini").string()));
  std::filesystem::remove_all(dir);
  ASSERT_TRUE(f.pose_check.has_value());
  EXPECT_NE(f.pose_check->status, "ok");
  ASSERT_FALSE(f.pose_check->violations.empty());
  EXPECT_THAT(f.pose_check->violations.front(), HasSubstr("3"));
  EXPECT_LT(f.pose_check->stroke_margin[3], 0.0);
}

TEST_F(LiveViewTest, TheStateWord) {
  nlohmann::json r = linuxcncRecord(1);
  EXPECT_EQ(liveState(connected(r)), "idle");
  r["interp_state"] = 2;
  EXPECT_EQ(liveState(connected(r)), "running");
  r["paused"] = true;
  EXPECT_EQ(liveState(connected(r)), "paused");
  r = linuxcncRecord(1);
  r["homed"][0] = false;
  EXPECT_EQ(liveState(connected(r)), "not homed");
  r["enabled"] = false;
  r["task_state"] = 3;
  EXPECT_EQ(liveState(connected(r)), "off");
  r["estop"] = true;
  r["task_state"] = 1;
  EXPECT_EQ(liveState(connected(r)), "estop");
  LinkSnapshot gone = connected(r);
  gone.connected = false;
  EXPECT_EQ(liveState(gone), "disconnected");
}

TEST(LiveMachine, AConfigurationWithoutGenhexkinsIsRefusedNamingItsIni) {
  const auto dir = std::filesystem::temp_directory_path() / "pkm-live-view-test";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "other.hal") << "loadrt trivkins\n";
  std::ofstream(dir / "m.ini") << "[HAL]\nHALFILE = other.hal\n[TRAJ]\nLINEAR_UNITS = mm\n";
  try {
    (void)liveMachine((dir / "m.ini").string());
    ADD_FAILURE() << "accepted";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("m.ini: none of the files its [HAL] HALFILE lines load"));
  }
  std::filesystem::remove_all(dir);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::live
