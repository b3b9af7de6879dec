// pkm: command-line interface of the pkm toolkit. Exit codes (docs/formats.md): 0 success, 1 a
// check failed or a target was missed, 2 usage or input error, 3 internal error.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "analyze_common.hpp"
#include "cli_common.hpp"
#include "pkm/core/error.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "pkm: kinematics, measurement analysis, calibration and compensation for parallel "
      "kinematic machine tools"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "pkm 0.1.0");
  pkm::cli::addHexapodCommands(app);
  pkm::cli::addExechonCommands(app);
  pkm::cli::addVolumetricCommand(app);
  pkm::cli::addSimulateCommand(app);
  pkm::cli::addAnalyzeCommand(app);
  pkm::cli::addCalibrateCommand(app);
  pkm::cli::addPlanPosesCommand(app);
  pkm::cli::addMachinesCommand(app);
  pkm::cli::addDemoCommand(app);
  pkm::cli::addRegisteredCommands(app);
  pkm::cli::setFooter(app, pkm::cli::kExitCodesHelp);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const pkm::cli::ExitCode& e) {
    std::fflush(stdout);
    return e.code;
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return pkm::cli::kExitUsage;
  } catch (const pkm::IoError& e) {
    std::fflush(stdout);
    fmt::print(stderr, "pkm: error: {}\n", e.what());
    return pkm::cli::kExitUsage;
  } catch (const pkm::InvalidArgument& e) {
    std::fflush(stdout);
    fmt::print(stderr, "pkm: error: {}\n", e.what());
    return pkm::cli::kExitUsage;
  } catch (const std::exception& e) {
    std::fflush(stdout);
    fmt::print(stderr, "pkm: internal error: {}\n", e.what());
    return pkm::cli::kExitInternal;
  }
  return 0;
}
