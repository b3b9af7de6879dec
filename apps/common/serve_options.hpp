// The options of `pkm serve`, shared by the `pkm` program (which checks them and hands the command
// to its sibling program `pkm-serve`) and by `pkm-serve` (which runs the server).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace pkm::cli {

/// `pkm serve [--host 127.0.0.1] [--port 8787] [--open]`.
struct ServeOptions {
  std::string host = "127.0.0.1";  ///< address to listen on
  int port = 8787;                 ///< TCP port; 0 = any free port
  bool open = false;               ///< open the page in the desktop's browser
};

/// Adds --host, --port and --open to `cmd`, bound to `o`.
inline void addServeOptions(CLI::App& cmd, ServeOptions& o) {
  cmd.add_option("--host",
                 o.host,
                 "address to listen on (default 127.0.0.1: this machine only; any other needs the "
                 "token in the printed URL)");
  cmd.add_option("--port", o.port, "port (default 8787; 0: any free port)")
      ->check(CLI::Range(0, 65535));
  cmd.add_flag("--open", o.open, "open the page in the desktop's browser");
}

/// The one-line description of `pkm serve`.
inline constexpr const char* kServeDescription =
    "the web application: the machine in 3-D, programs by G-code or blocks checked in a "
    "simulator, campaigns (docs/web.md); serves until Ctrl-C";

}  // namespace pkm::cli
