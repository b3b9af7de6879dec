// The options of `pkm serve`, shared by the `pkm` program (which checks them and hands the command
// to its sibling program `pkm-serve`) and by `pkm-serve` (which runs the server).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace pkm::cli {

/// `pkm serve [--host 127.0.0.1] [--port 8787] [--open] [--linuxcnc [INI]]`.
struct ServeOptions {
  std::string host = "127.0.0.1";  ///< address to listen on
  int port = 8787;                 ///< TCP port; 0 = any free port
  bool open = false;               ///< open the page in the desktop's browser
  bool linuxcnc = false;           ///< follow the LinuxCNC running on this host (docs/linuxcnc.md)
  std::string linuxcnc_ini;        ///< its INI ("": the one LinuxCNC reports)
};

/// Adds --host, --port, --open and --linuxcnc to `cmd`, bound to `o`.
inline void addServeOptions(CLI::App& cmd, ServeOptions& o) {
  cmd.add_option("--host",
                 o.host,
                 "address to listen on (default 127.0.0.1: this machine only; any other needs the "
                 "token in the printed URL)");
  cmd.add_option("--port", o.port, "port (default 8787; 0: any free port)")
      ->check(CLI::Range(0, 65535));
  cmd.add_flag("--open", o.open, "open the page in the desktop's browser");
  cmd.add_option_function<std::string>(
         "--linuxcnc",
         [&o](const std::string& ini) {
           o.linuxcnc = true;
           o.linuxcnc_ini = ini;
         },
         "follow the LinuxCNC running on this host (read only): the Machine view shows it live; "
         "INI: its configuration (default: the one LinuxCNC reports)")
      ->expected(0, 1);
}

/// The one-line description of `pkm serve`.
inline constexpr const char* kServeDescription =
    "the web application: the machine in 3-D, programs by G-code or blocks checked in a "
    "simulator, campaigns (docs/web.md); serves until Ctrl-C";

}  // namespace pkm::cli
