// The automated calibration's routes of server::Api (POST /api/live/calibration and its cancel,
// confirm and state) with stand-ins for LinuxCNC's reader and commander: every refusal (no token,
// a wrong token, a foreign Origin, a request replayed after the server started again, no
// confirmation, LinuxCNC in E-stop or busy, a second routine) sends LinuxCNC nothing (the
// commander does not even start, or is asked only for its status); a routine stops the machine
// when the page's connection drops or the page cancels. The routine itself runs on a real
// LinuxCNC in tests/linuxcnc/live_calibration_test.py.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "pkm/server/api.hpp"
#include "support/commander_standin.hpp"
#include "support/linuxcnc_config.hpp"
#include "support/linuxcnc_record.hpp"
#include "support/scratch_files.hpp"

namespace pkm::server {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using ::testing::HasSubstr;

class LiveCalibrationRoutes : public pkm::test::ScratchDirTest {
 protected:
  LiveCalibrationRoutes() : ScratchDirTest("live_cal_routes") {}
  void SetUp() override {
    ScratchDirTest::SetUp();
    ini_ = pkm::test::writeHexapodDefaultConfig(dir_);
    record_ = pkm::test::linuxcncRecord(1, {0, 0, 200, 0, 0, 0}, {1, 2, 3, 4, 5, 6}, ini_);
    record_["linear_units"] = 1.0;
  }

  /// A server following the stand-in reader, commanding through the stand-in commander.
  ServerOptions options() const {
    ServerOptions o;
    o.port = 8787;
    o.linuxcnc = true;
    o.linuxcnc_ini = ini_;
    o.live.command = {
        "/bin/sh", "-c", "printf '%s\\n' \"$1\"; cat >/dev/null", "reader", record_.dump()};
    o.commander.command = {
        "/usr/bin/python3", "-u", "-c", pkm::test::kCommanderStandIn, record_.dump(), sent()};
    o.heartbeat_s = 0.05;
    return o;
  }
  std::string sent() const { return (dir_ / "sent.log").string(); }
  /// The lines the commander received ("" : it never started).
  std::string sentText() const {
    std::ifstream in(sent());
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }

  static Request start(const std::string& token, const std::string& origin = "") {
    const Json body = {{"confirm", true},
                       {"gauges", {"g.0", "g.1", "g.2"}},
                       {"stations", 14},
                       {"holdout_stations", 1}};
    return {"POST", "/api/live/calibration", body.dump(), "127.0.0.1:8787", origin, token, ""};
  }
  static Request withToken(const std::string& path, const std::string& token) {
    return {"POST", path, R"({"install": true})", "127.0.0.1:8787", "", "", "pkm_token=" + token};
  }

  std::string ini_;
  Json record_;
};

TEST_F(LiveCalibrationRoutes, RefusalsSendLinuxcncNothing) {
  Api api(options());
  LiveCalibrationJob job;
  EXPECT_EQ(api.startLiveCalibration(start(""), job).status, 401);                    // no token
  EXPECT_EQ(api.startLiveCalibration(start(std::string(64, 'a')), job).status, 401);  // wrong one
  // The right token from a foreign page (its Origin): refused too.
  EXPECT_EQ(api.startLiveCalibration(start(api.token(), "http://evil.example"), job).status, 403);
  // A request replayed against the server started again: the old token is not this launch's.
  const std::string old_token = api.token();
  Api again(options());
  const Response replayed = again.startLiveCalibration(start(old_token), job);
  EXPECT_EQ(replayed.status, 401);
  EXPECT_THAT(replayed.body, HasSubstr("nothing was sent to the machine"));
  // The routes that answer the routine need the token as well.
  EXPECT_EQ(api.handle({"POST", "/api/live/calibration/cancel", "{}", "127.0.0.1:8787", "", "", ""})
                .status,
            401);
  EXPECT_EQ(again.handle(withToken("/api/live/calibration/confirm", old_token)).status, 401);
  // No explicit confirmation, no gauges.
  Request unconfirmed = start(api.token());
  unconfirmed.body = R"({"gauges": ["g.0", "g.1", "g.2"]})";
  EXPECT_EQ(api.startLiveCalibration(unconfirmed, job).status, 400);
  Request no_gauges = start(api.token());
  no_gauges.body = R"({"confirm": true, "gauges": ["g.0"]})";
  EXPECT_EQ(api.startLiveCalibration(no_gauges, job).status, 400);
  EXPECT_EQ(job.routine, nullptr);
  EXPECT_EQ(sentText(), "");  // the commander never started
  EXPECT_EQ(api.handle(withToken("/api/live/calibration/confirm", api.token())).status, 404);
}

TEST_F(LiveCalibrationRoutes, NothingMovesWhileLinuxcncIsInEstopOrBusy) {
  for (const auto& [field, value, why] :
       {std::tuple<const char*, Json, const char*>{"estop", true, "E-stop"},
        {"interp_state", 2, "running a program"}}) {
    record_ = pkm::test::linuxcncRecord(1, {0, 0, 200, 0, 0, 0}, {1, 2, 3, 4, 5, 6}, ini_);
    record_["linear_units"] = 1.0;
    record_[field] = value;
    Api api(options());
    LiveCalibrationJob job;
    const Response r = api.startLiveCalibration(start(api.token()), job);
    EXPECT_EQ(r.status, 409) << why;
    EXPECT_THAT(r.body, HasSubstr(why));
    std::istringstream lines(sentText());
    for (std::string line; std::getline(lines, line);)
      EXPECT_THAT(line, HasSubstr(R"("op":"status")")) << why;
    fs::remove(sent());
  }
}

/// Runs an admitted routine on a thread; its events are collected, `write` fails once `drop`.
struct Running {
  Running(Api& api, LiveCalibrationJob& job)
      : thread([this, &api, &job] {
          api.runLiveCalibration(job, [this](const std::string& chunk) {
            const std::lock_guard lock(mutex);
            if (drop) return false;
            events += chunk;
            return true;
          });
          finished = true;
        }) {}
  ~Running() { thread.join(); }
  bool saw(const std::string& text) {
    const std::lock_guard lock(mutex);
    return events.find(text) != std::string::npos;
  }
  std::mutex mutex;
  std::string events;
  bool drop = false;
  std::atomic<bool> finished{false};
  std::thread thread;
};

/// Waits up to 20 s for `done`.
template <typename F>
bool eventually(F done) {
  for (int i = 0; i < 2000 && !done(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  return done();
}

TEST_F(LiveCalibrationRoutes, ADroppedConnectionAbortsTheMoveAtOnce) {
  Api api(options());
  LiveCalibrationJob job;
  ASSERT_EQ(api.startLiveCalibration(start(api.token()), job).status, 200);
  // A second routine is refused while this one holds the machine.
  LiveCalibrationJob second;
  EXPECT_EQ(api.startLiveCalibration(start(api.token()), second).status, 409);
  Running run(api, job);
  ASSERT_TRUE(eventually([&] { return sentText().find(R"("op":"mdi")") != std::string::npos; }));
  EXPECT_THAT(api.handle({"GET", "/api/live/calibration", "", "127.0.0.1:8787", "", "", ""}).body,
              HasSubstr(R"("running":true)"));
  {
    const std::lock_guard lock(run.mutex);
    run.drop = true;  // the page's connection is gone: the next heartbeat cannot be written
  }
  ASSERT_TRUE(eventually([&] { return run.finished.load(); }));
  EXPECT_THAT(sentText(), HasSubstr(R"("op":"abort")"));
  EXPECT_THAT(api.handle({"GET", "/api/live/calibration", "", "127.0.0.1:8787", "", "", ""}).body,
              HasSubstr(R"("running":false)"));
}

TEST_F(LiveCalibrationRoutes, CancelStopsTheMachine) {
  Api api(options());
  LiveCalibrationJob job;
  ASSERT_EQ(api.startLiveCalibration(start(api.token()), job).status, 200);
  Running run(api, job);
  ASSERT_TRUE(eventually([&] { return sentText().find(R"("op":"mdi")") != std::string::npos; }));
  EXPECT_EQ(api.handle(withToken("/api/live/calibration/confirm", api.token())).status, 409);
  EXPECT_EQ(api.handle(withToken("/api/live/calibration/cancel", api.token())).status, 200);
  ASSERT_TRUE(eventually([&] { return run.finished.load(); }));
  EXPECT_TRUE(run.saw("event: cancelled"));
  EXPECT_FALSE(run.saw("event: result"));
  EXPECT_THAT(sentText(), HasSubstr(R"("op":"abort")"));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::server
