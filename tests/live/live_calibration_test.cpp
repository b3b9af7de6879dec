// live::calibrateLive's refusals, with a stand-in for LinuxCNC's commander: nothing is sent that
// moves the machine when LinuxCNC runs another configuration, is in E-stop, not homed, in inches
// or with a tool length offset, or when an earlier run's files would be overwritten; the routine
// itself runs in tests/linuxcnc/live_calibration_test.py (a real LinuxCNC).
#include "pkm/live/live_calibration.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "pkm/core/error.hpp"
#include "support/linuxcnc_config.hpp"
#include "support/linuxcnc_record.hpp"
#include "support/scratch_files.hpp"

namespace pkm::live {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

/// Answers every request with the status record argv[1] (and an empty answer to the rest).
const char* kStatusOnly = R"PY(
import json, sys
record = json.loads(sys.argv[1])
for line in sys.stdin:
    r = json.loads(line)
    if r.get("op") == "abort":
        continue
    print(json.dumps({"id": r.get("id"), "ok": True, "status": record}), flush=True)
)PY";

class LiveCalibrationRefusals : public pkm::test::ScratchDirTest {
 protected:
  LiveCalibrationRefusals() : ScratchDirTest("live_calibration") {}
  void SetUp() override {
    ScratchDirTest::SetUp();
    ini_ = pkm::test::writeHexapodDefaultConfig(dir_);
    request_.ini = ini_;
    request_.gauges = {"g.0", "g.1", "g.2"};
    request_.out = (dir_ / "run").string();
  }

  /// The refusal calibrateLive gives when LinuxCNC reports `record`, and what was sent.
  std::pair<std::string, std::vector<std::string>> refusal(const nlohmann::json& record) {
    CommanderOptions o;
    o.command = {"/usr/bin/python3", "-u", "-c", kStatusOnly, record.dump()};
    LinuxcncCommander cnc(o);
    std::string why = "accepted";
    try {
      (void)calibrateLive(request_, cnc);
    } catch (const std::exception& e) {
      why = e.what();
    }
    return {why, cnc.log()};
  }

  nlohmann::json ready() const {
    nlohmann::json r = pkm::test::linuxcncRecord(1, {0, 0, 200, 0, 0, 0}, {1, 2, 3, 4, 5, 6}, ini_);
    r["linear_units"] = 1.0;
    return r;
  }

  std::string ini_;
  LiveCalibrationRequest request_;
};

TEST_F(LiveCalibrationRefusals, NothingMovesUnlessLinuxcncMayMove) {
  auto expectRefused = [&](nlohmann::json record, const std::string& why) {
    const auto [what, sent] = refusal(record);
    EXPECT_THAT(what, HasSubstr(why));
    for (const std::string& line : sent) EXPECT_THAT(line, HasSubstr(R"("op":"status")")) << why;
  };
  nlohmann::json r = ready();
  r["estop"] = true;
  expectRefused(r, "LinuxCNC cannot be moved: LinuxCNC is in E-stop");
  r = ready();
  r["homed"][4] = false;
  expectRefused(r, "not every joint is homed");
  r = ready();
  r["interp_state"] = 2;
  expectRefused(r, "running a program or command");
  r = ready();
  r["ini"] = "/elsewhere/other.ini";
  expectRefused(r, "LinuxCNC runs /elsewhere/other.ini, not");
  r = ready();
  r["linear_units"] = 1.0 / 25.4;
  expectRefused(r, "needs a configuration in mm");
  r = ready();
  r["tool_offset"] = {0, 0, 12.5};
  expectRefused(r, "tool length offset is active (G43)");
  EXPECT_FALSE(fs::exists(dir_ / "run"));
}

TEST_F(LiveCalibrationRefusals, AnEarlierRunIsNotOverwrittenWithoutForce) {
  write("run/commands.log", "an earlier run\n");
  const auto [what, sent] = refusal(ready());
  EXPECT_THAT(what, HasSubstr("run/commands.log: exists; pass --force"));
  for (const std::string& line : sent) EXPECT_THAT(line, HasSubstr(R"("op":"status")"));
  EXPECT_EQ(pkm::test::slurp(dir_ / "run/commands.log"), "an earlier run\n");
}

TEST_F(LiveCalibrationRefusals, TooFewStationsForTheUnknownsAreRefusedBeforeAnythingIsAsked) {
  request_.stations.count = 13;  // 39 equations for 42 unknowns
  const auto [what, sent] = refusal(ready());
  EXPECT_THAT(what, HasSubstr("--stations: at least 14"));
  EXPECT_TRUE(sent.empty() || sent.size() == 1);  // the commander's own first status, at most
  request_.stations.count = 14;
  EXPECT_NO_THROW(request_.validate());
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::live
