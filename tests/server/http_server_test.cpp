// server::HttpServer on a real socket: port 0, the Host rule and the body limit at the transport,
// a long job not blocking other requests and the job limit (503), a campaign streamed as
// server-sent events with its report, and a clean stop.
#include "pkm/server/http_server.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <httplib.h>

#include <atomic>
#include <nlohmann/json.hpp>
#include <thread>
#include <vector>

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

TEST_F(HttpServerTest, ALongJobBlocksNeitherReadsNorTheJobLimit) {
  ServerOptions o;
  o.max_jobs = 1;
  start(o);
  const std::string body =
      Json{{"machine", "hexapod-default"}, {"program", longProgram(20'000)}}.dump();
  // Two long runs at once (each takes over a second): one runs, the other is refused; reads are
  // answered while the run goes on.
  std::atomic<int> running{2};
  int status[2] = {0, 0};
  std::vector<std::thread> jobs;
  for (int k = 0; k < 2; ++k)
    jobs.emplace_back([&, k] {
      const auto r = client().Post("/api/gcode/run", body, "application/json");
      status[k] = r ? r->status : -1;
      --running;
    });
  int reads_during_run = 0;
  while (running > 0) {
    const auto read = client().Get("/api/machines");
    ASSERT_TRUE(read);
    EXPECT_EQ(read->status, 200);
    if (running > 0) ++reads_during_run;
  }
  for (std::thread& t : jobs) t.join();
  EXPECT_EQ(std::min(status[0], status[1]), 200);
  EXPECT_EQ(std::max(status[0], status[1]), 503);
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

}  // namespace PKM_TEST_NS
}  // namespace pkm::server
