// pkm-serve: the program behind `pkm serve [--host H] [--port P] [--open] [--linuxcnc [INI]]`, the
// web application and its JSON API (server::HttpServer, docs/web.md) until Ctrl-C. `pkm serve`
// checks its options and replaces itself with this program, so that the HTTP server's libraries
// (cpp-httplib, OpenSSL, zlib, brotli) are loaded by the server alone, not by every pkm run
// (docs/architecture.md, "Programs"). Exit codes as pkm's (docs/formats.md).
#include <fmt/format.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <filesystem>
#include <thread>

#include "exit_codes.hpp"
#include "pkm/core/error.hpp"
#include "pkm/server/http_server.hpp"
#include "serve_options.hpp"

namespace {

using pkm::cli::kExitInternal;
using pkm::cli::kExitUsage;

/// Opens `url` in the desktop's browser, if there is one (best effort, detached).
void openBrowser(const std::string& url) {
  if (std::system("command -v xdg-open >/dev/null 2>&1") != 0) {
    fmt::print(stderr, "pkm: note: no xdg-open here; open {} yourself\n", url);
    return;
  }
  const std::string cmd = fmt::format("xdg-open '{}' >/dev/null 2>&1 &", url);
  if (std::system(cmd.c_str()) != 0) fmt::print(stderr, "pkm: note: could not open {}\n", url);
}

void runServe(const pkm::cli::ServeOptions& o) {
  // SIGINT and SIGTERM are taken by a thread of ours (sigtimedwait), which stops the server:
  // blocked here, before any thread starts, so that every thread inherits the mask.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  pkm::server::ServerOptions options;
  options.host = o.host;
  options.port = o.port;
  options.linuxcnc = o.linuxcnc;
  if (!o.linuxcnc_ini.empty())
    options.linuxcnc_ini = std::filesystem::absolute(o.linuxcnc_ini).string();
  pkm::server::HttpServer http(options);
  const int port = http.bind();
  // The URL carries the per-launch token (docs/web.md, "Security"): the page opened with it may
  // command the machine; off loopback, every route needs it.
  const std::string url =
      fmt::format("http://{}:{}/?token={}", options.host, port, http.api().token());
  fmt::print("pkm: serving {}\n", url);
  std::fflush(stdout);
  if (o.open) openBrowser(url);
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

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{pkm::cli::kServeDescription, "pkm serve"};
  pkm::cli::ServeOptions options;
  pkm::cli::addServeOptions(app, options);
  try {
    app.parse(argc, argv);
    runServe(options);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kExitUsage;
  } catch (const pkm::InvalidArgument& e) {
    fmt::print(stderr, "pkm: error: {}\n", e.what());
    return kExitUsage;
  } catch (const pkm::IoError& e) {
    fmt::print(stderr, "pkm: error: {}\n", e.what());
    return kExitUsage;
  } catch (const std::exception& e) {
    fmt::print(stderr, "pkm: internal error: {}\n", e.what());
    return kExitInternal;
  }
  return 0;
}
