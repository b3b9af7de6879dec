// server::HttpServer under connections that never make a request (docs/web.md, "Robustness"):
// 200 silent ones, 200 kept alive after one request, and 200 that send half a header and then a
// byte every half second (slowloris) do not delay the page's requests: each is answered within
// kAnswerLimit, where httplib's thread per connection made it wait 52-59 s. 16 runs at once (a
// user with several tabs) all get 200: the two slots' jobs run, the others wait in the queue.
// Also: a header above 64 kB is answered 431, a pipelined second request on a connection is
// served.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <httplib.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <vector>

#include "pkm/server/http_server.hpp"

namespace pkm::server {
namespace PKM_TEST_NS {

using Clock = std::chrono::steady_clock;

/// The median answer the page must get with the stalling connections open (the bound),
/// and the slowest one allowed on a loaded CI machine.
constexpr double kMedianLimitS = 0.100;
constexpr double kAnswerLimitS = 1.0;
constexpr int kEach = 200;

int connectTo(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<std::uint16_t>(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof(a)) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

void sendText(int fd, const std::string& text) {
  (void)::send(fd, text.data(), text.size(), MSG_NOSIGNAL);
}

/// Everything `fd` sends until it closes or 2 s pass.
std::string receiveAll(int fd) {
  timeval tv{2, 0};
  ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof(tv));
  std::string out;
  char buf[4096];
  for (ssize_t n; (n = ::recv(fd, buf, sizeof(buf), 0)) > 0;)
    out.append(buf, static_cast<std::size_t>(n));
  return out;
}

class HttpServerLoad : public ::testing::Test {
 protected:
  void SetUp() override {
    ServerOptions o;
    o.port = 0;
    server_ = std::make_unique<HttpServer>(o);
    port_ = server_->bind();
    thread_ = std::thread([this] { server_->listen(); });
    host_ = "Host: 127.0.0.1:" + std::to_string(port_) + "\r\n";
  }
  void TearDown() override {
    server_->stop();
    thread_.join();
  }
  std::unique_ptr<HttpServer> server_;
  std::thread thread_;
  int port_ = 0;
  std::string host_;
};

TEST_F(HttpServerLoad, SilentKeptAliveAndSlowHeaderConnectionsDoNotStallThePage) {
  std::vector<int> silent, kept, slow;
  for (int i = 0; i < kEach; ++i) silent.push_back(connectTo(port_));
  for (int i = 0; i < kEach; ++i) {
    kept.push_back(connectTo(port_));
    sendText(kept.back(), "GET /api/campaigns HTTP/1.1\r\n" + host_ + "\r\n");
  }
  for (int i = 0; i < kEach; ++i) {
    slow.push_back(connectTo(port_));
    sendText(slow.back(), "GET /api/machines HTTP/1.1\r\n" + host_ + "X-Slow: ");
  }
  std::atomic<bool> done{false};
  std::thread trickle([&] {
    while (!done) {
      for (const int fd : slow) sendText(fd, "a");
      std::this_thread::sleep_for(std::chrono::milliseconds(500));
    }
  });
  std::vector<double> seconds;
  for (int k = 0; k < 20; ++k) {
    httplib::Client page("127.0.0.1", port_);  // a new connection each time, as after an idle gap
    const auto t0 = Clock::now();
    const auto r = page.Get("/api/machines");
    seconds.push_back(std::chrono::duration<double>(Clock::now() - t0).count());
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 200);
  }
  done = true;
  trickle.join();
  std::sort(seconds.begin(), seconds.end());
  EXPECT_LT(seconds[seconds.size() / 2], kMedianLimitS);
  EXPECT_LT(seconds.back(), kAnswerLimitS);
  std::printf(
      "with %d silent, %d kept-alive and %d slow-header connections: median %.1f ms, "
      "slowest %.1f ms\n",
      kEach,
      kEach,
      kEach,
      1e3 * seconds[seconds.size() / 2],
      1e3 * seconds.back());
  for (const auto* fds : {&silent, &kept, &slow})
    for (const int fd : *fds) ::close(fd);
}

TEST_F(HttpServerLoad, SixteenRunsAtOnceAreAllAnswered) {
  std::string program = "G0 X0 Y0 Z200\nF600\n";
  for (int i = 0; i < 2000; ++i) program += i % 2 ? "G1 X10\n" : "G1 X-10\n";
  program += "M2\n";
  const std::string body =
      nlohmann::json{{"machine", "hexapod-default"}, {"program", program}, {"frames", 200}}.dump();
  std::vector<int> status(16, 0);
  std::vector<std::thread> runs;
  for (std::size_t k = 0; k < status.size(); ++k)
    runs.emplace_back([&, k] {
      httplib::Client c("127.0.0.1", port_);
      c.set_read_timeout(120, 0);
      const auto r = c.Post("/api/gcode/run", body, "application/json");
      status[k] = r ? r->status : -1;
    });
  for (std::thread& t : runs) t.join();
  EXPECT_EQ(std::count(status.begin(), status.end(), 200), 16);
}

TEST_F(HttpServerLoad, AnOversizedHeaderIs431AndPipelinedRequestsAreServed) {
  const int big = connectTo(port_);
  sendText(big, "GET /api/machines HTTP/1.1\r\n" + host_ + "X-Big: " + std::string(70'000, 'a'));
  EXPECT_EQ(receiveAll(big).rfind("HTTP/1.1 431", 0), 0u);
  ::close(big);
  const int two = connectTo(port_);
  const std::string get = "GET /api/campaigns HTTP/1.1\r\n" + host_ + "\r\n";
  sendText(two, get + "GET /api/campaigns HTTP/1.1\r\n" + host_ + "Connection: close\r\n\r\n");
  const std::string answers = receiveAll(two);
  ::close(two);
  std::size_t count = 0;
  for (std::size_t at = answers.find("HTTP/1.1 200"); at != std::string::npos;
       at = answers.find("HTTP/1.1 200", at + 1))
    ++count;
  EXPECT_EQ(count, 2u) << answers.substr(0, 500);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::server
