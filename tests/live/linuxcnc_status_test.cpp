// The reader's lines parsed (pkm/live/linuxcnc_status.hpp): a status record field by field, the
// reader's error and fatal lines, the derived states, and malformed lines refused with the field.
#include "pkm/live/linuxcnc_status.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "pkm/core/error.hpp"
#include "support/linuxcnc_record.hpp"

namespace pkm::live {
namespace PKM_TEST_NS {

using pkm::test::linuxcncRecord;
using ::testing::HasSubstr;

TEST(LinuxcncStatus, AStatusRecordIsReadFieldByField) {
  nlohmann::json j = linuxcncRecord(7, {1, 2, 21, 3, -2, 5}, {20.5, 21, 21.5, 22, 22.5, 23});
  j["file"] = "/tmp/part.ngc";
  j["current_line"] = 12;
  j["tool"] = 3;
  j["g5x_offset"] = {1, 2, 3, 0, 0, 0};
  const ReaderLine r = parseReaderLine(j.dump());
  ASSERT_EQ(r.kind, ReaderLine::Kind::kStatus);
  const LinuxcncStatus& s = r.status;
  EXPECT_EQ(s.sequence, 7);
  EXPECT_EQ(s.ini, "/nowhere/hexapod.ini");
  EXPECT_EQ(s.joint_actual.size(), 6u);
  EXPECT_EQ(s.joint_commanded[5], 23.0);
  EXPECT_EQ(s.pose_commanded[2], 21.0);
  EXPECT_EQ(s.pose_commanded[4], -2.0);
  EXPECT_EQ(s.task_mode, TaskMode::kMdi);
  EXPECT_EQ(s.task_state, TaskState::kOn);
  EXPECT_EQ(s.file, "/tmp/part.ngc");
  EXPECT_EQ(s.current_line, 12);
  EXPECT_EQ(s.tool, 3);
  EXPECT_EQ(s.g5x_offset[1], 2.0);
  EXPECT_TRUE(s.allHomed());
  EXPECT_FALSE(s.busy());
  EXPECT_TRUE(s.readyToMove());
}

TEST(LinuxcncStatus, EstopUnhomedOrRunningIsNotReadyToMove) {
  nlohmann::json j = linuxcncRecord(1);
  j["estop"] = true;
  j["task_state"] = 1;
  EXPECT_FALSE(parseReaderLine(j.dump()).status.readyToMove());
  j = linuxcncRecord(1);
  j["homed"][4] = false;
  EXPECT_FALSE(parseReaderLine(j.dump()).status.allHomed());
  EXPECT_FALSE(parseReaderLine(j.dump()).status.readyToMove());
  j = linuxcncRecord(1);
  j["interp_state"] = 2;
  EXPECT_TRUE(parseReaderLine(j.dump()).status.busy());
  EXPECT_FALSE(parseReaderLine(j.dump()).status.readyToMove());
}

TEST(LinuxcncStatus, ErrorAndFatalLinesCarryTheirMessage) {
  const ReaderLine e = parseReaderLine(R"({"error": "LinuxCNC is not running on this host"})");
  EXPECT_EQ(e.kind, ReaderLine::Kind::kError);
  EXPECT_EQ(e.message, "LinuxCNC is not running on this host");
  const ReaderLine f = parseReaderLine(R"({"fatal": "python3 cannot import the linuxcnc module"})");
  EXPECT_EQ(f.kind, ReaderLine::Kind::kFatal);
  EXPECT_THAT(f.message, HasSubstr("linuxcnc module"));
}

TEST(LinuxcncStatus, MalformedLinesAreRefusedNamingTheField) {
  const auto message = [](const std::string& line) {
    try {
      (void)parseReaderLine(line);
    } catch (const IoError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_THAT(message("Traceback (most recent call last):"), HasSubstr("not a JSON object"));
  EXPECT_THAT(message("[1, 2]"), HasSubstr("not a JSON object"));
  nlohmann::json j = linuxcncRecord(1);
  j.erase("pose_commanded");
  EXPECT_THAT(message(j.dump()), HasSubstr("no \"pose_commanded\""));
  j = linuxcncRecord(1);
  j["joint_actual"][2] = nullptr;  // the reader's NaN
  EXPECT_THAT(message(j.dump()), HasSubstr("\"joint_actual\"[2] is not a finite number"));
  j = linuxcncRecord(1);
  j["joints"] = 40;
  EXPECT_THAT(message(j.dump()), HasSubstr("\"joints\" 40 is not 1..16"));
  j = linuxcncRecord(1);
  j["homed"] = {true, true};
  EXPECT_THAT(message(j.dump()), HasSubstr("\"homed\" is not one flag per joint"));
  j = linuxcncRecord(1);
  j["task_mode"] = 9;
  EXPECT_THAT(message(j.dump()), HasSubstr("\"task_mode\" 9 is not one of 1..3"));
  j = linuxcncRecord(1);
  j["estop"] = 0;
  EXPECT_THAT(message(j.dump()), HasSubstr("\"estop\" is not true or false"));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::live
