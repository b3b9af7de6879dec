// server::HttpServer on a real socket: port 0, the Host rule and the body limit at the transport,
// a long job not blocking other requests and the job limit (503), a campaign streamed as
// server-sent events with its report, and a clean stop.
#include "pkm/server/http_server.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <httplib.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>
#include <vector>

#include "support/commander_standin.hpp"
#include "support/linuxcnc_config.hpp"
#include "support/linuxcnc_record.hpp"

namespace pkm::server {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;
using Json = nlohmann::json;

class HttpServerTest : public ::testing::Test {
 protected:
  void start(ServerOptions o) {
    o.port = 0;
    server_ = std::make_unique<HttpServer>(o);
    port_ = server_->bind();
    thread_ = std::thread([this] { server_->listen(); });
  }
  void TearDown() override {
    if (server_) server_->stop();
    if (thread_.joinable()) thread_.join();
  }
  httplib::Client client() {
    httplib::Client c("127.0.0.1", port_);
    c.set_read_timeout(120, 0);
    return c;
  }
  /// A program of `n` short moves (a long job).
  static std::string longProgram(int n) {
    std::string p = "G0 X0 Y0 Z200\nF600\n";
    for (int i = 0; i < n; ++i) p += i % 2 ? "G1 X10\n" : "G1 X-10\n";
    p += "M2\n";
    return p;
  }
  std::unique_ptr<HttpServer> server_;
  std::thread thread_;
  int port_ = 0;
};

TEST_F(HttpServerTest, ServesOnAFreePortAndChecksTheHost) {
  start({});
  ASSERT_GT(port_, 0);
  httplib::Client c = client();
  const auto r = c.Get("/api/machines");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  const auto foreign =
      c.Get("/api/machines", {{"Host", "rebound.example:" + std::to_string(port_)}});
  ASSERT_TRUE(foreign);
  EXPECT_EQ(foreign->status, 403);
  const auto page = c.Get("/");
  ASSERT_TRUE(page);
  EXPECT_THAT(page->get_header_value("Content-Type"), HasSubstr("text/html"));
}

TEST_F(HttpServerTest, OnAnAddressOfTheNetworkOnlyTheTokenOpensThePage) {
  // Bound to every address: the URL's ?token= opens the page and sets the cookie a browser sends
  // with the page's own requests; without it, or with another launch's, 401.
  ServerOptions o;
  o.host = "0.0.0.0";
  start(o);
  const std::string token = server_->api().token();
  ASSERT_EQ(token.size(), 64u);
  httplib::Client c = client();
  const httplib::Headers host{{"Host", "0.0.0.0:" + std::to_string(port_)}};
  const auto none = c.Get("/api/machines", host);
  ASSERT_TRUE(none);
  EXPECT_EQ(none->status, 401);
  const auto page = c.Get("/?token=" + token, host);
  ASSERT_TRUE(page);
  EXPECT_EQ(page->status, 200);
  EXPECT_THAT(page->get_header_value("Set-Cookie"), HasSubstr("pkm_token=" + token));
  EXPECT_THAT(page->get_header_value("Set-Cookie"), HasSubstr("HttpOnly"));
  httplib::Headers with_cookie = host;
  with_cookie.emplace("Cookie", "pkm_token=" + token);
  const auto api = c.Get("/api/machines", with_cookie);
  ASSERT_TRUE(api);
  EXPECT_EQ(api->status, 200);
  httplib::Headers stale = host;
  stale.emplace("Cookie", "pkm_token=" + std::string(64, '0'));
  const auto refused = c.Get("/api/machines", stale);
  ASSERT_TRUE(refused);
  EXPECT_EQ(refused->status, 401);
}
TEST_F(HttpServerTest, BodiesAboveTheLimitGet413) {
  ServerOptions o;
  o.max_body = 1000;
  start(o);
  const auto r = client().Post("/api/ik", std::string(5000, ' '), "application/json");
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 413);
}

TEST_F(HttpServerTest, LongJobsQueueAndBlockNoReads) {
  ServerOptions o;
  o.max_jobs = 1;
  o.max_queued = 1;
  start(o);
  const std::string body =
      Json{{"machine", "hexapod-default"}, {"program", longProgram(20'000)}}.dump();
  // Three long runs at once (each takes over a second) on one slot and a queue of one: one runs,
  // one waits for it and is answered 200 too, the third finds the queue full: 503 with
  // Retry-After. Reads are answered while the runs go on, and the queue shows in GET /api/jobs.
  std::atomic<int> running{3};
  int status[3] = {0, 0, 0};
  std::string retry[3];
  std::vector<std::thread> jobs;
  for (int k = 0; k < 3; ++k)
    jobs.emplace_back([&, k] {
      const auto r = client().Post("/api/gcode/run", body, "application/json");
      status[k] = r ? r->status : -1;
      if (r) retry[k] = r->get_header_value("Retry-After");
      --running;
    });
  int reads_during_run = 0;
  bool saw_queue = false;
  while (running > 0) {
    const auto read = client().Get("/api/jobs");
    ASSERT_TRUE(read);
    EXPECT_EQ(read->status, 200);
    saw_queue = saw_queue || Json::parse(read->body)["queued"].size() == 1;
    if (running > 0) ++reads_during_run;
  }
  for (std::thread& t : jobs) t.join();
  std::sort(std::begin(status), std::end(status));
  EXPECT_EQ(status[0], 200);
  EXPECT_EQ(status[1], 200);
  EXPECT_EQ(status[2], 503);
  EXPECT_EQ(retry[0] + retry[1] + retry[2], "2");
  EXPECT_TRUE(saw_queue);
  EXPECT_GT(reads_during_run, 0);
}

TEST_F(HttpServerTest, ACampaignStreamsItsProgressAndReport) {
  start({});
  httplib::Client c = client();
  std::string stream;
  httplib::Request req;
  req.method = "POST";
  req.path = "/api/campaign";
  req.body = R"({"campaign": "default"})";
  req.set_header("Content-Type", "application/json");
  req.content_receiver = [&](const char* data, std::size_t n, std::uint64_t, std::uint64_t) {
    stream.append(data, n);
    return true;
  };
  const auto r = c.send(req);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200);
  EXPECT_THAT(stream, HasSubstr("event: progress\n"));
  const std::size_t at = stream.find("event: result\ndata: ");
  ASSERT_NE(at, std::string::npos) << stream.substr(0, 2000);
  const std::size_t from = at + 20;
  const Json result = Json::parse(stream.substr(from, stream.find('\n', from) - from));
  EXPECT_TRUE(result["all_pass"].get<bool>());
  const auto report = c.Get(result["report"].get<std::string>());
  ASSERT_TRUE(report);
  EXPECT_EQ(report->status, 200);
  EXPECT_THAT(report->body, HasSubstr("<html"));
}

TEST_F(HttpServerTest, ACalibrationStopsTheMachineWhenThePageConnectionDrops) {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("pkm_http_routine_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string ini = pkm::test::writeHexapodDefaultConfig(dir);
  Json record = pkm::test::linuxcncRecord(1, {0, 0, 200, 0, 0, 0}, {1, 2, 3, 4, 5, 6}, ini);
  record["linear_units"] = 1.0;
  const std::string sent = (dir / "sent.log").string();
  ServerOptions o;
  o.linuxcnc = true;
  o.linuxcnc_ini = ini;
  o.live.command = {"/bin/sh", "-c", "printf '%s\\n' \"$1\"; cat >/dev/null", "r", record.dump()};
  o.commander.command = {
      "/usr/bin/python3", "-u", "-c", pkm::test::kCommanderStandIn, record.dump(), sent};
  start(o);
  auto sentText = [&] {
    std::ifstream in(sent);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  };
  httplib::Client c = client();
  httplib::Request req;
  req.method = "POST";
  req.path = "/api/live/calibration?token=" + server_->api().token();
  req.body = R"({"confirm": true, "gauges": ["g.0", "g.1", "g.2"], "stations": 14})";
  req.set_header("Content-Type", "application/json");
  std::string stream;
  req.content_receiver = [&](const char* data, std::size_t n, std::uint64_t, std::uint64_t) {
    stream.append(data, n);
    // The page goes away once the machine moves (closed tab, dropped network).
    return sentText().find(R"("op":"mdi")") == std::string::npos;
  };
  (void)c.send(req);
  EXPECT_THAT(stream, HasSubstr("event: started"));
  bool aborted = false;
  for (int i = 0; i < 500 && !aborted; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    aborted = sentText().find(R"("op":"abort")") != std::string::npos;
  }
  EXPECT_TRUE(aborted) << sentText();
  fs::remove_all(dir);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::server
