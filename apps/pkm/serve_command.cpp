// `pkm serve [--host 127.0.0.1] [--port 8787] [--open] [--linuxcnc [INI]]`: checks the options and
// replaces this process with the program `pkm-serve` beside it (apps/pkm-serve), which runs the web
// application. The server's libraries (cpp-httplib with OpenSSL, zlib and brotli) are then loaded
// only by the server: every other pkm command starts about 2 ms sooner (docs/architecture.md,
// "Programs").
#include <fmt/format.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "cli_common.hpp"
#include "pkm/core/error.hpp"
#include "serve_options.hpp"

namespace pkm::cli {
namespace {

[[noreturn]] void execServe(const ServeOptions& o) {
  const std::filesystem::path server = programDirectory() / "pkm-serve";
  if (std::error_code ec; !std::filesystem::exists(server, ec))
    throw IoError(
        fmt::format("{}: not here: this pkm was built without its web server "
                    "(PKM_BUILD_SERVER off, or cpp-httplib or node missing: run "
                    "scripts/setup.sh and build again)",
                    server.string()));
  std::vector<std::string> args = {
      server.string(), "--host", o.host, "--port", std::to_string(o.port)};
  if (o.open) args.emplace_back("--open");
  if (o.linuxcnc) {
    args.emplace_back("--linuxcnc");
    if (!o.linuxcnc_ini.empty()) args.push_back(o.linuxcnc_ini);
  }
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  ::execv(server.c_str(), argv.data());
  throw std::runtime_error(fmt::format("cannot run {} ({}); it is built and installed beside pkm",
                                       server.string(),
                                       std::strerror(errno)));
}

void addServe(CLI::App& app) {
  auto o = std::make_shared<ServeOptions>();
  CLI::App* cmd = app.add_subcommand("serve", kServeDescription);
  addServeOptions(*cmd, *o);
  cmd->callback([o] { execServe(*o); });
}

const CommandRegistration kRegisterServe{120, "serve", &addServe};

}  // namespace
}  // namespace pkm::cli
