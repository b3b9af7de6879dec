// The live routes of server::Api (GET /api/live, POST /api/live/connect and /disconnect) with a
// stand-in LinuxCNC reader: not following, following from the start (--linuxcnc) and after
// Connect, the record checked on the configuration's machine, a reader that ends, and the
// security rules (methods, Origin, token) that every route keeps.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <thread>

#include "pkm/core/error.hpp"
#include "pkm/server/api.hpp"
#include "support/linuxcnc_record.hpp"
#include "support/linuxcnc_sample.hpp"

namespace pkm::server {
namespace PKM_TEST_NS {

using Json = nlohmann::json;
using ::testing::HasSubstr;

/// LinuxCNC's hexapod-sim at x y z a b c = 2 -1 22 3 -4 10 with genhexkins' strut lengths.
Json simRecord(const std::string& ini) {
  return pkm::test::linuxcncRecord(
      3,
      {2, -1, 22, 3, -4, 10},
      {31.597194, 31.713899, 29.975223, 32.850082, 27.921167, 33.441616},
      ini);
}

/// A server following a stand-in reader that writes `line` after `delay` seconds.
ServerOptions following(const std::string& line, bool from_start, const char* delay = "0") {
  ServerOptions o;
  o.port = 8787;
  o.linuxcnc = from_start;
  o.live.command = {"/bin/sh",
                    "-c",
                    "sleep \"$2\"; printf '%s\\n' \"$1\"; cat >/dev/null",
                    "reader",
                    line,
                    delay};
  return o;
}

Response get(Api& api, const std::string& path) {
  return api.handle({"GET", path, "", "127.0.0.1:8787", "", "", ""});
}
Response post(Api& api, const std::string& path, const std::string& origin = "") {
  return api.handle({"POST", path, "{}", "127.0.0.1:8787", origin, "", ""});
}

/// GET /api/live until `done` holds (at most 10 s).
Json poll(Api& api, const std::function<bool(const Json&)>& done) {
  Json j;
  for (int i = 0; i < 1000; ++i) {
    const Response r = get(api, "/api/live");
    EXPECT_EQ(r.status, 200) << r.body;
    j = Json::parse(r.body);
    if (done(j)) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return j;
}

TEST(ApiLive, NotFollowingSaysHowToStart) {
  Api api(following("", false));
  const Json j = Json::parse(get(api, "/api/live").body);
  EXPECT_EQ(j["following"], false);
  EXPECT_EQ(j["state"], "disconnected");
  EXPECT_THAT(j["reason"].get<std::string>(), HasSubstr("pkm serve --linuxcnc"));
}

TEST(ApiLive, TheRecordIsCheckedOnTheConfigurationsMachine) {
  const std::string ini = (pkm::test::linuxcncHexapodSim() / "hexapod.ini").string();
  if (!std::filesystem::exists(ini)) GTEST_SKIP() << "no LinuxCNC sample at " << ini;
  Api api(following(simRecord(ini).dump(), true));
  const Json j = poll(api, [](const Json& j) { return j["connected"] == true; });
  ASSERT_EQ(j["connected"], true) << j.dump();
  EXPECT_EQ(j["state"], "idle");
  EXPECT_EQ(j["machine"]["units"], "inch");
  EXPECT_EQ(j["status"]["pose_commanded"][2], 22.0);
  EXPECT_EQ(j["check"]["status"], "ok");
  EXPECT_LT(j["joint_disagreement"].get<double>(), 1e-6);
  EXPECT_EQ(j["status"]["mode"], "mdi");
  EXPECT_EQ(j["status"]["executing_line"], 0);
}

TEST(ApiLive, TheFollowedMachineAndProgramAreServed) {
  const std::string ini = (pkm::test::linuxcncHexapodSim() / "hexapod.ini").string();
  if (!std::filesystem::exists(ini)) GTEST_SKIP() << "no LinuxCNC sample at " << ini;
  const auto program = std::filesystem::temp_directory_path() / "pkm-api-live-test.ngc";
  std::ofstream(program) << "G20 G90\nG0 X0 Y0 Z20\nM2\n";
  Json record = simRecord(ini);
  record["file"] = program.string();
  Api api(following(record.dump(), true, "1"));               // the first record comes after 1 s
  EXPECT_EQ(get(api, "/api/machines/linuxcnc").status, 400);  // before the first record
  (void)poll(api, [](const Json& j) { return j["connected"] == true; });
  const Json list = Json::parse(get(api, "/api/machines").body);
  EXPECT_EQ(list.back()["name"], "linuxcnc");
  EXPECT_EQ(list.back()["live"], true);
  const Response m = get(api, "/api/machines/linuxcnc");
  ASSERT_EQ(m.status, 200) << m.body;
  EXPECT_EQ(Json::parse(m.body)["units"], "inch");
  const Response p = get(api, "/api/live/program");
  ASSERT_EQ(p.status, 200) << p.body;
  EXPECT_EQ(Json::parse(p.body)["text"], "G20 G90\nG0 X0 Y0 Z20\nM2\n");
  std::filesystem::remove(program);
  EXPECT_EQ(get(api, "/api/live/program").status, 404);  // LinuxCNC's file is gone
}

TEST(ApiLive, NoProgramIsNotFound) {
  Api api(following(pkm::test::linuxcncRecord(1).dump(), true));
  (void)poll(api, [](const Json& j) { return j["connected"] == true; });
  EXPECT_EQ(get(api, "/api/live/program").status, 404);
  Api idle(following("", false));
  EXPECT_EQ(get(idle, "/api/live/program").status, 404);
}

TEST(ApiLive, ConnectStartsFollowingAndDisconnectStops) {
  Api api(following(pkm::test::linuxcncRecord(1).dump(), false));
  EXPECT_EQ(Json::parse(get(api, "/api/live").body)["following"], false);
  ASSERT_EQ(post(api, "/api/live/connect").status, 200);
  const Json j = poll(api, [](const Json& j) { return j["connected"] == true; });
  EXPECT_EQ(j["following"], true);
  // The record names an INI that does not exist: the state is shown, the machine is not.
  EXPECT_THAT(j["machine_error"].get<std::string>(), HasSubstr("/nowhere/hexapod.ini"));
  EXPECT_FALSE(j.contains("check"));
  ASSERT_EQ(post(api, "/api/live/disconnect").status, 200);
  EXPECT_EQ(Json::parse(get(api, "/api/live").body)["following"], false);
}

TEST(ApiLive, AReaderThatEndsIsADisconnection) {
  Api api(following(R"({"error": "LinuxCNC is not running on this host"})", true));
  const Json j = poll(
      api, [](const Json& j) { return !j["reason"].get<std::string>().starts_with("waiting"); });
  EXPECT_EQ(j["connected"], false);
  EXPECT_EQ(j["state"], "disconnected");
  EXPECT_THAT(j["reason"].get<std::string>(), HasSubstr("not running"));
}

TEST(ApiLive, MethodsOriginAndTokenAreChecked) {
  Api api(following(pkm::test::linuxcncRecord(1).dump(), false));
  EXPECT_EQ(post(api, "/api/live").status, 405);
  EXPECT_EQ(get(api, "/api/live/connect").status, 405);
  EXPECT_EQ(post(api, "/api/live/connect", "http://evil.example").status, 403);
  EXPECT_EQ(Json::parse(get(api, "/api/live").body)["following"], false);  // nothing started
  ServerOptions remote = following("", false);
  remote.host = "0.0.0.0";
  Api open(remote);
  EXPECT_EQ(open.handle({"GET", "/api/live", "", "0.0.0.0:8787", "", "", ""}).status, 401);
  EXPECT_EQ(open.handle({"POST", "/api/live/connect", "{}", "0.0.0.0:8787", "", "", ""}).status,
            401);
}

TEST(ApiLive, AnIniThatDoesNotExistIsRefusedAtTheStart) {
  ServerOptions o = following("", true);
  o.linuxcnc_ini = "/nowhere/at/all.ini";
  EXPECT_THROW(Api{o}, InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::server
