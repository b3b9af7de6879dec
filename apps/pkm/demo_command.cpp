// `pkm demo`: the main job on the embedded default machines (workflow::runDemo): describe the
// hexapod, follow a 5-axis path through IK, check every pose, solve FK back along it as a servo
// loop would, and summarise accuracy, iterations, limits and speed; then the Exechon part.
#include <cstdio>
#include <memory>

#include "cli_common.hpp"
#include "pkm/workflow/demo.hpp"

namespace pkm::cli {

void addDemoCommand(CLI::App& app) {
  auto request = std::make_shared<workflow::DemoRequest>();
  CLI::App* demo = app.add_subcommand(
      "demo", "describe the default hexapod and run an IK/FK round trip along a path");
  addMachineOptions(*demo, request->machine, request->ini);
  demo->add_option("--points", request->points, "number of path poses")
      ->check(CLI::Range(2, 10000000));
  demo->callback([request] {
    CliRunControl run;
    const workflow::DemoResult result = workflow::runDemo(*request, run.control());
    run.finish();
    std::string text = io::hexapodDemoText(result.hexapod);
    if (result.exechon) text += io::exechonDemoText(*result.exechon);
    writeTextOutput("", text);
    if (!result.pass()) {
      std::fflush(stdout);
      std::fputs("pkm: the demo's round trip failed its tolerance\n", stderr);
      throw ExitCode{kExitCheckFailed};
    }
  });
}

}  // namespace pkm::cli
