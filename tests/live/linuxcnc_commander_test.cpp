// live::LinuxcncCommander with a stand-in for the commander program (the protocol of
// src/live/linuxcnc_bridge.py, "the commander"): requests answered in order, LinuxCNC's
// refusals and errors reported with their words, stray lines skipped, every line sent logged,
// a commander that cannot reach LinuxCNC refused at once, and the commander's input closed when
// the object goes (its cue to abort any motion). Also live::motionRefusal's words.
#include "pkm/live/linuxcnc_commander.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "pkm/core/error.hpp"
#include "support/linuxcnc_record.hpp"
#include "support/scratch_files.hpp"

namespace pkm::live {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

/// A stand-in commander: answers as the real one does; on the end of its input writes "aborted"
/// to the file argv[2].
const char* kStandIn = R"PY(
import json, sys
record = json.loads(sys.argv[1])
for line in sys.stdin:
    r = json.loads(line)
    op, rid = r.get("op"), r.get("id")
    if op == "abort":
        continue
    if op == "mdi" and "REFUSE" in r["line"]:
        print(json.dumps({"id": rid, "ok": False, "error": "refused: LinuxCNC is in E-stop"}), flush=True)
        continue
    if op == "mdi":
        print("tool_mmap_user(): tool mmap not available", flush=True)
        print(json.dumps({"id": 0, "ok": True}), flush=True)
        rec = dict(record, joint_commanded=[float(len(r["line"]))] * 6)
        print(json.dumps({"id": rid, "ok": True, "status": rec}), flush=True)
    elif op == "hal_get":
        print(json.dumps({"id": rid, "ok": True, "values": [1.5, True][:len(r["pins"])]}), flush=True)
    elif op == "hal_set":
        print(json.dumps({"id": rid, "ok": True}), flush=True)
    else:
        print(json.dumps({"id": rid, "ok": True, "status": record}), flush=True)
open(sys.argv[2], "w").write("aborted")
)PY";

CommanderOptions standIn(const std::string& marker) {
  CommanderOptions o;
  o.command = {"/usr/bin/python3",
               "-u",
               "-c",
               kStandIn,
               pkm::test::linuxcncRecord(1, {0, 0, 20, 0, 0, 0}).dump(),
               marker};
  return o;
}

TEST(LinuxcncCommander, AnswersInOrderAndLogsWhatItSends) {
  const auto marker = pkm::test::scratchPath("commander", "aborted");
  std::filesystem::remove(marker);
  std::vector<std::string> seen;
  {
    CommanderOptions o = standIn(marker.string());
    o.on_sent = [&seen](const std::string& line) { seen.push_back(line); };
    LinuxcncCommander cnc(o);
    EXPECT_TRUE(cnc.status().readyToMove());
    const LinuxcncStatus st = cnc.mdi("G53 G0 X1");  // the stray lines before it are skipped
    EXPECT_EQ(st.joint_commanded.at(0), 9.0);        // the stand-in echoes the line's length
    EXPECT_EQ(cnc.halValues({"a.b", "c.d"}), (std::vector<double>{1.5, 1.0}));
    cnc.setPin("pkmhexkins.hold", "1");
    try {
      (void)cnc.mdi("REFUSE");
      FAIL() << "a refusal was not reported";
    } catch (const IoError& e) {
      EXPECT_STREQ(e.what(), "LinuxCNC: refused: LinuxCNC is in E-stop");
    }
    EXPECT_THROW((void)cnc.mdi("G0 X1\nG0 X2"), InvalidArgument);  // one line only
    const std::vector<std::string> log = cnc.log();
    ASSERT_EQ(log.size(), 6u);
    EXPECT_THAT(log[0], HasSubstr(R"("op":"status")"));  // the start-up check
    EXPECT_THAT(log[2], HasSubstr(R"("line":"G53 G0 X1")"));
    EXPECT_THAT(log[4], HasSubstr(R"("op":"hal_set")"));
    EXPECT_EQ(seen, log);
    EXPECT_FALSE(std::filesystem::exists(marker));
  }
  EXPECT_EQ(pkm::test::slurp(marker), "aborted");  // its input closed: the abort cue
}

TEST(LinuxcncCommander, ACommanderThatCannotReachLinuxcncIsRefused) {
  CommanderOptions o;
  o.command = {"/bin/sh",
               "-c",
               R"SH(echo '{"fatal": "LinuxCNC is not running on this host (emcStatusBuffer)"}')SH"};
  try {
    LinuxcncCommander cnc(o);
    FAIL() << "started";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("LinuxCNC is not running on this host"));
  }
  o.command = {"/nonexistent/pkm-commander"};
  EXPECT_THROW(LinuxcncCommander{o}, IoError);
  o.command = {"/bin/true"};
  EXPECT_THROW(LinuxcncCommander{o}, IoError);  // ended without an answer
  o.move_timeout_s = 0.0;
  EXPECT_THROW(LinuxcncCommander{o}, InvalidArgument);
}

TEST(MotionRefusal, SaysWhyLinuxcncMustNotMove) {
  auto status = [](auto change) {
    nlohmann::json r = pkm::test::linuxcncRecord(1);
    change(r);
    return parseReaderLine(r.dump()).status;
  };
  EXPECT_EQ(motionRefusal(status([](auto&) {})), "");
  EXPECT_EQ(motionRefusal(status([](auto& r) { r["estop"] = true; })), "LinuxCNC is in E-stop");
  EXPECT_EQ(motionRefusal(status([](auto& r) { r["enabled"] = false; })), "the machine is off");
  EXPECT_EQ(motionRefusal(status([](auto& r) { r["homed"][2] = false; })),
            "not every joint is homed");
  EXPECT_EQ(motionRefusal(status([](auto& r) { r["interp_state"] = 2; })),
            "LinuxCNC is running a program or command");
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::live
