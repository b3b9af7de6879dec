// `pkm serve [--host 127.0.0.1] [--port 8787] [--open]`: the web application and its JSON API
// (server::HttpServer, docs/web.md) until Ctrl-C.
#include <fmt/format.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <thread>

#include "cli_common.hpp"
#include "pkm/server/http_server.hpp"

namespace pkm::cli {
namespace {

struct ServeArgs {
  server::ServerOptions options;
  bool open = false;
};

/// Opens `url` in the desktop's browser, if there is one (best effort, detached).
void openBrowser(const std::string& url) {
  if (std::system("command -v xdg-open >/dev/null 2>&1") != 0) {
    fmt::print(stderr, "pkm: note: no xdg-open here; open {} yourself\n", url);
    return;
  }
  const std::string cmd = fmt::format("xdg-open '{}' >/dev/null 2>&1 &", url);
  if (std::system(cmd.c_str()) != 0) fmt::print(stderr, "pkm: note: could not open {}\n", url);
}

void runServe(ServeArgs& a) {
  // SIGINT and SIGTERM are taken by a thread of ours (sigtimedwait), which stops the server:
  // blocked here, before any thread starts, so that every thread inherits the mask.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  server::HttpServer http(a.options);
  const int port = http.bind();
  const std::string url = fmt::format("http://{}:{}/", a.options.host, port);
  fmt::print("pkm: serving {}\n", url);
  std::fflush(stdout);
  if (a.open) openBrowser(url);
  std::atomic<bool> done{false};
  std::thread watcher([&] {
    const timespec tick{0, 200'000'000};
    while (!done.load()) {
      if (sigtimedwait(&signals, nullptr, &tick) > 0) {
        fmt::print(stderr, "pkm: stopping\n");
        http.stop();
        return;
      }
    }
  });
  http.listen();
  done = true;
  watcher.join();
}

void addServe(CLI::App& app) {
  auto a = std::make_shared<ServeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "serve",
      "the web application: the machine in 3-D, programs by G-code or blocks checked in a "
      "simulator, campaigns (docs/web.md); serves until Ctrl-C");
  cmd->add_option("--host",
                  a->options.host,
                  "address to listen on (default 127.0.0.1: this "
                  "machine only)");
  cmd->add_option("--port", a->options.port, "port (default 8787; 0: any free port)")
      ->check(CLI::Range(0, 65535));
  cmd->add_flag("--open", a->open, "open the page in the desktop's browser");
  cmd->callback([a] { runServe(*a); });
}

const CommandRegistration kRegisterServe{120, &addServe};

}  // namespace
}  // namespace pkm::cli
