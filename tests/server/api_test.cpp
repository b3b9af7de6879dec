// server::Api in process: the routes' answers, the error statuses (400, 403, 404, 405, 413, 422,
// 503) and the security rules (Host, token, Origin, no paths from requests), without a socket.
#include "pkm/server/api.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <sstream>
#include <thread>

#include "support/linuxcnc_sample.hpp"

namespace pkm::server {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;
using Json = nlohmann::json;

constexpr int kPort = 8787;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class ApiTest : public ::testing::Test {
 protected:
  ApiTest() : api_(options()) {}
  static ServerOptions options() {
    ServerOptions o;
    o.port = kPort;
    o.max_body = 1 << 20;
    return o;
  }
  Response get(const std::string& path, const std::string& host = "127.0.0.1:8787") {
    return api_.handle({"GET", path, "", host, "", "", ""});
  }
  Response post(const std::string& path, const std::string& body, const std::string& origin = "") {
    return api_.handle({"POST", path, body, "localhost:8787", origin, "", ""});
  }
  static Json body(const Response& r) { return Json::parse(r.body); }
  Api api_;
};

TEST_F(ApiTest, ListsTheBuiltInMachines) {
  const Response r = get("/api/machines");
  ASSERT_EQ(r.status, 200) << r.body;
  const Json j = body(r);
  ASSERT_GE(j.size(), 4u);
  EXPECT_EQ(j[0]["name"], "hexapod-default");
  EXPECT_EQ(j[0]["type"], "hexapod");
  EXPECT_EQ(j[0]["units"], "mm");
  bool exechon = false;
  for (const Json& m : j) exechon = exechon || m["type"] == "exechon";
  EXPECT_TRUE(exechon);
}

TEST(ApiSamples, LinuxcncsHexapodSimIsAMachineWhereItIsInstalled) {
  const std::filesystem::path sim = test::linuxcncHexapodSim();
  if (!std::filesystem::exists(sim)) GTEST_SKIP() << sim << " absent (scripts/fetch-linuxcnc.sh)";
  ServerOptions o;
  o.sample_root = sim.parent_path().parent_path().parent_path().parent_path().string();
  Api api(o);
  const Response list = api.handle({"GET", "/api/machines", "", "127.0.0.1:8787", "", "", ""});
  ASSERT_EQ(list.status, 200);
  EXPECT_THAT(list.body, HasSubstr(R"("name":"linuxcnc-hexapod-sim")"));
  const Response m =
      api.handle({"GET", "/api/machines/linuxcnc-hexapod-sim", "", "127.0.0.1:8787", "", "", ""});
  ASSERT_EQ(m.status, 200) << m.body;
  const Response run =
      api.handle({"POST",
                  "/api/gcode/run",
                  R"({"machine": "linuxcnc-hexapod-sim", "program": "G0 X1\nM2\n"})",
                  "localhost:8787",
                  "",
                  "",
                  ""});
  EXPECT_EQ(run.status, 200) << run.body;
}

TEST_F(ApiTest, AMachineWithItsDrawingAtHome) {
  const Json j = body(get("/api/machines/hexapod-linuxcnc-sim"));
  EXPECT_EQ(j["units"], "inch");
  EXPECT_EQ(j["machine"]["name"], "hexapod-linuxcnc-sim");  // the describe --json document
  EXPECT_EQ(j["drawing"]["status"], "ok");
  EXPECT_EQ(j["drawing"]["base_points"].size(), 6u);
  EXPECT_EQ(j["home"][2], 20.0);
  const Json e = body(get("/api/machines/mxt700s-like"));
  EXPECT_EQ(e["type"], "exechon");
  EXPECT_EQ(e["joints"].size(), 5u);
  EXPECT_EQ(e["drawing"]["wrist_points"].size(), 1u);
}

TEST_F(ApiTest, RequestsNeverNameAPath) {
  const Response r = get("/api/machines/..%2f..%2fetc%2fpasswd");
  EXPECT_EQ(r.status, 400);
  EXPECT_THAT(body(r)["error"].get<std::string>(), HasSubstr("unknown machine"));
  const Response ik =
      post("/api/ik", R"({"machine": "/etc/passwd", "poses": [[0, 0, 200, 0, 0, 0]]})");
  EXPECT_EQ(ik.status, 400);
  EXPECT_EQ(get("/../../etc/passwd").status, 404);
  EXPECT_EQ(get("/api/nothing").status, 404);
}

TEST_F(ApiTest, ForeignHostsAndOriginsAreRefused) {
  EXPECT_EQ(get("/api/machines", "evil.example:8787").status, 403);  // DNS rebinding
  EXPECT_EQ(get("/api/machines", "127.0.0.1:9999").status, 403);
  EXPECT_EQ(get("/api/machines", "").status, 403);
  EXPECT_EQ(get("/api/machines", "localhost:8787").status, 200);
  const std::string ik = R"({"machine": "hexapod-default", "poses": [[0, 0, 200, 0, 0, 0]]})";
  EXPECT_EQ(post("/api/ik", ik, "http://evil.example").status, 403);
  EXPECT_EQ(post("/api/ik", ik, "null").status, 403);
  EXPECT_EQ(post("/api/ik", ik, "http://localhost:8787").status, 200);
  EXPECT_EQ(post("/api/ik", ik).status, 200);  // no Origin: not a browser page
}

TEST(ApiToken, EveryLaunchHasItsTokenALoopbackServerReadsWithoutIt) {
  for (const char* h : {"127.0.0.1", "127.1.2.3", "localhost", "::1", "[::1]"})
    EXPECT_TRUE(isLoopbackHost(h)) << h;
  for (const char* h : {"0.0.0.0", "192.168.1.5", "::", "127.0.0.1.evil", "128.0.0.1", "host"})
    EXPECT_FALSE(isLoopbackHost(h)) << h;
  ServerOptions o;
  o.port = kPort;
  Api loopback(o);
  EXPECT_EQ(loopback.token().size(), 64u);  // the routes that command the machine need it
  // Reads need none on loopback, even with a stale cookie of an earlier launch.
  EXPECT_EQ(loopback.handle({"GET", "/api/machines", "", "127.0.0.1:8787", "", "", ""}).status,
            200);
  EXPECT_EQ(loopback
                .handle({"GET",
                         "/api/machines",
                         "",
                         "127.0.0.1:8787",
                         "",
                         "",
                         "pkm_token=" + std::string(64, '0')})
                .status,
            200);
  o.host = "0.0.0.0";
  const Api a(o), b(o);
  EXPECT_EQ(a.token().size(), 64u);
  EXPECT_EQ(a.token().find_first_not_of("0123456789abcdef"), std::string::npos);
  EXPECT_NE(a.token(), b.token());  // a new secret at every launch
}

TEST(ApiToken, AServerReachableFromOtherMachinesAnswersOnlyWithItsToken) {
  ServerOptions o;
  o.host = "0.0.0.0";
  o.port = kPort;
  Api api(o);
  const std::string& token = api.token();
  const auto get =
      [&](const std::string& path, const std::string& query, const std::string& cookie) {
        return api.handle({"GET", path, "", "0.0.0.0:8787", "", query, cookie});
      };
  // Nothing, not even the page, without the token (401 with what to do).
  for (const char* path : {"/", "/api/machines", "/index.html"}) {
    const Response none = get(path, "", "");
    EXPECT_EQ(none.status, 401) << path;
    EXPECT_THAT(none.body, HasSubstr("open the URL `pkm serve` printed"));
  }
  EXPECT_EQ(get("/api/machines", "0123", "").status, 401);
  EXPECT_EQ(get("/api/machines", "", std::string(kTokenCookie) + "=" + token + "0").status, 401);
  EXPECT_EQ(get("/api/machines", token.substr(0, 63), "").status, 401);
  // The URL's token: answered, with a cookie that keeps it (HttpOnly, this site only).
  const Response opened = get("/", token, "");
  EXPECT_EQ(opened.status, 200);
  EXPECT_EQ(opened.set_cookie,
            std::string(kTokenCookie) + "=" + token + "; Path=/; HttpOnly; SameSite=Strict");
  const Response later = get("/api/machines", "", "theme=dark; pkm_token=" + token + "; x=1");
  EXPECT_EQ(later.status, 200);
  EXPECT_EQ(later.set_cookie, "");
  // The token does not lift the other rules: a foreign Origin still may not change anything.
  const std::string ik = R"({"machine": "hexapod-default", "poses": [[0, 0, 200, 0, 0, 0]]})";
  EXPECT_EQ(api.handle({"POST",
                        "/api/ik",
                        ik,
                        "0.0.0.0:8787",
                        "http://evil.example",
                        "",
                        "pkm_token=" + token})
                .status,
            403);
  EXPECT_EQ(
      api.handle({"POST", "/api/ik", ik, "0.0.0.0:8787", "", "", "pkm_token=" + token}).status,
      200);
  // A request replayed against the server started again: its token is another.
  Api again(o);
  EXPECT_EQ(again.handle({"GET", "/api/machines", "", "0.0.0.0:8787", "", "", "pkm_token=" + token})
                .status,
            401);
}

TEST_F(ApiTest, StatusCodesForBadRequests) {
  EXPECT_EQ(post("/api/ik", "{not json").status, 400);
  EXPECT_EQ(post("/api/ik", "[1, 2]").status, 400);
  EXPECT_EQ(post("/api/ik", R"({"machine": "hexapod-default", "poses": [[0, 0]]})").status, 400);
  EXPECT_EQ(post("/api/ik", R"({"poses": []})").status, 400);
  EXPECT_EQ(get("/api/ik").status, 405);
  EXPECT_EQ(post("/api/ik", std::string(2 << 20, ' ')).status, 413);
  const Response bad = post("/api/gcode/run", R"({"machine": "hexapod-default", "name": "p.ngc",
      "program": "G0 X0 Y0 Z200\nG1 X1 Q\n"})");
  EXPECT_EQ(bad.status, 422);
  EXPECT_EQ(body(bad)["name"], "p.ngc");
  EXPECT_EQ(body(bad)["line"], 2);
  EXPECT_EQ(post("/api/gcode/run", R"({"machine": "hexapod-default", "program": "G0 X1",
      "max_points": -1})")
                .status,
            400);
  // A runaway loop (within the interpreter's iteration guard) is refused by the server's point
  // budget at its line in about a second, not after 31 s and 3.5 GB.
  const Response runaway = post("/api/gcode/run", R"({"machine": "hexapod-default",
      "name": "r.ngc", "program": "G0 X0 Y0 Z200\nF600\n#1=0\no1 while [#1 LT 9000000]\nG1 X10\nG1 X-10\n#1=[#1+1]\no1 endwhile\nM2\n"})");
  EXPECT_EQ(runaway.status, 422);
  EXPECT_EQ(body(runaway)["line"], 6);  // motion 1,000,001: the G0 and 500,000 passes
  EXPECT_THAT(body(runaway)["error"].get<std::string>(), HasSubstr("more than 1000000 motions"));
}

TEST_F(ApiTest, PosesCheckedWithMargins) {
  const Response r = post("/api/ik", R"({"machine": "hexapod-default",
      "poses": [[0, 0, 200, 0, 0, 0], [0, 0, -300, 0, 0, 0]]})");
  ASSERT_EQ(r.status, 200) << r.body;
  const Json j = body(r);
  EXPECT_EQ(j["joints"].size(), 6u);
  EXPECT_EQ(j["rows"][0]["status"], "ok");
  EXPECT_EQ(j["rows"][0]["joints"].size(), 6u);
  EXPECT_GT(j["rows"][0]["clearance"].get<double>(), 0.0);
  EXPECT_EQ(j["rows"][1]["status"], "stroke");
}

TEST_F(ApiTest, UploadedMachinesAreHeldAndNamedInErrors) {
  Json up{{"filename", "my-hexapod.json"},
          {"text", slurp(std::string(PKM_SOURCE_DIR) + "/data/machines/hexapod-default.json")}};
  const Response r = post("/api/machines", up.dump());
  ASSERT_EQ(r.status, 200) << r.body;
  const std::string name = body(r)["name"];
  EXPECT_EQ(name, "upload-1-my-hexapod");
  EXPECT_EQ(get("/api/machines/" + name).status, 200);
  const Json list = body(get("/api/machines"));
  EXPECT_EQ(list.back()["name"], name);
  EXPECT_EQ(list.back()["uploaded"], true);
  // A broken LinuxCNC file: 422 naming the upload (not the server's folder) and the line.
  const Json hal{{"filename", "../../kinematics.hal"},
                 {"text", "loadrt genhexkins\nsetp genhexkins.base.0.x oops\n"}};
  const Response bad = post("/api/machines", hal.dump());
  ASSERT_EQ(bad.status, 422) << bad.body;
  EXPECT_EQ(body(bad)["name"], "kinematics.hal");
  EXPECT_EQ(body(bad)["line"], 2);
  EXPECT_EQ(post("/api/machines", R"({"filename": "m.txt", "text": "x"})").status, 400);
}

TEST_F(ApiTest, AProgramRunsWithPathAndViolations) {
  const Response r = post("/api/gcode/run", R"({"machine": "hexapod-default", "name": "v.ngc",
      "program": "G0 X0 Y0 Z200\nG1 Z100 F600\nG1 Z-300\nM2\n", "max_points": 50})");
  ASSERT_EQ(r.status, 200) << r.body;
  const Json j = body(r);
  EXPECT_EQ(j["program"], "v.ngc");
  EXPECT_FALSE(j["ok"].get<bool>());
  EXPECT_LE(j["path"]["t"].size(), 50u + 16u);
  EXPECT_EQ(j["path"]["q"][0].size(), 6u);
  ASSERT_GT(j["violations"].size(), 0u);
  EXPECT_EQ(j["violations"][0]["check"], "stroke");
  EXPECT_EQ(j["violations"][0]["line"], 3);
}

TEST_F(ApiTest, ShapesAreTheLibrarys) {
  const Response r = post("/api/gcode/shape",
                          R"({"shape": "drill", "values": {"holes": 2, "radius": 5, "top": 0}})");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(body(r)["lines"][0], "G0 X5 Y0 Z2");
  EXPECT_EQ(body(r)["lines"].size(), 6u);
  EXPECT_EQ(post("/api/gcode/shape", R"({"shape": "cube"})").status, 400);
  EXPECT_EQ(post("/api/gcode/shape", R"({"shape": "drill", "values": {"holes": "2"}})").status,
            400);
  EXPECT_EQ(post("/api/gcode/shape", R"({"shape": "pocket", "values": {"stepover": 1e-9}})").status,
            400);
}

TEST_F(ApiTest, ANamedRunIsCancelled) {
  std::string program = "G0 X0 Y0 Z200\nF600\n";
  for (int i = 0; i < 100'000; ++i) program += i % 2 ? "G1 X10\n" : "G1 X-10\n";
  program += "M2\n";
  const std::string body =
      Json{{"machine", "hexapod-default"}, {"program", program}, {"job", "long-run"}}.dump();
  Response run;
  std::thread t([&] { run = post("/api/gcode/run", body); });
  int cancel = 0;
  for (int k = 0; k < 2000 && cancel != 200; ++k) {
    cancel = post("/api/jobs/long-run/cancel", "").status;  // 404 until the run has started
    if (cancel != 200) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  t.join();
  EXPECT_EQ(cancel, 200);
  EXPECT_EQ(run.status, 409) << run.body.substr(0, 200);
  EXPECT_EQ(post("/api/jobs/long-run/cancel", "").status, 404);  // no longer running
  EXPECT_EQ(post("/api/gcode/run", R"({"machine": "hexapod-default", "program": "G0 X0",
      "job": "../x"})")
                .status,
            400);
}

TEST_F(ApiTest, CompensateReturnsTheProgram) {
  const Response r = post("/api/gcode/compensate", R"({"machine": "hexapod-default",
      "nominal": "hexapod-default", "program": "G0 X0 Y0 Z200\nG1 X10 F600\nM2\n"})");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_THAT(body(r)["text"].get<std::string>(), HasSubstr("G1 X"));
  EXPECT_EQ(body(r)["max_correction_mm"], 0.0);  // the same machine: nothing to correct
}

TEST_F(ApiTest, TheFrontEndIsEmbedded) {
  const Response page = get("/");
  EXPECT_EQ(page.status, 200);
  EXPECT_THAT(page.content_type, HasSubstr("text/html"));
  EXPECT_EQ(page.cache_control, "");  // the page itself: never cached (no-store)
  // The bundle under its content-hashed name, kept a year; the page names it.
  std::smatch js, css;
  ASSERT_TRUE(std::regex_search(page.body, js, std::regex(R"(/app\.([0-9a-f]{16})\.js)")));
  ASSERT_TRUE(std::regex_search(page.body, css, std::regex(R"(/app\.([0-9a-f]{16})\.css)")));
  const Response bundle = get(js[0].str());
  EXPECT_EQ(bundle.status, 200);
  EXPECT_THAT(bundle.content_type, HasSubstr("javascript"));
  EXPECT_EQ(bundle.cache_control, "public, max-age=31536000, immutable");
  EXPECT_EQ(get(css[0].str()).status, 200);
  EXPECT_EQ(get("/app.0000000000000000.js").status, 404);  // another build's name
}

TEST_F(ApiTest, CampaignsAreListedAndTheirStreamNeedsTheTransport) {
  const Json j = body(get("/api/campaigns"));
  EXPECT_EQ(j[0]["name"], "default");
  CampaignJob job;
  EXPECT_EQ(
      api_.startCampaign(
              {"POST", "/api/campaign", R"({"campaign": "nope"})", "localhost:8787", "", "", ""},
              job)
          .status,
      400);
  EXPECT_EQ(get("/api/campaign/7/report.html").status, 404);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::server
