// pkm: command-line interface of the pkm toolkit. Exit codes (docs/formats.md): 0 success, 1 a
// check failed or a target was missed, 2 usage or input error, 3 internal error.
#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <exception>
#include <iterator>
#include <string_view>

#include "analyze_common.hpp"
#include "cli_common.hpp"
#include "pkm/core/error.hpp"

namespace {

/// A command group main() adds itself: its subcommand name and what adds it.
struct BuiltInGroup {
  std::string_view name;
  void (*add)(CLI::App&);
};
/// In the order of `pkm --help` (the self-registering groups follow).
constexpr BuiltInGroup kBuiltInGroups[] = {{"hexapod", &pkm::cli::addHexapodCommands},
                                           {"exechon", &pkm::cli::addExechonCommands},
                                           {"volumetric", &pkm::cli::addVolumetricCommand},
                                           {"simulate", &pkm::cli::addSimulateCommand},
                                           {"analyze", &pkm::cli::addAnalyzeCommand},
                                           {"calibrate", &pkm::cli::addCalibrateCommand},
                                           {"plan-poses", &pkm::cli::addPlanPosesCommand},
                                           {"machines", &pkm::cli::addMachinesCommand},
                                           {"demo", &pkm::cli::addDemoCommand}};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "pkm: kinematics, measurement analysis, calibration and compensation for parallel "
      "kinematic machine tools"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "pkm 0.1.0");
  // A command line that names its command group gets that group alone: building every group's
  // options costs about 0.5 ms a run, a share of short jobs run once per file. Anything else (no
  // group, --help, --version, a misspelt group) gets them all, so that help lists them and errors
  // read as before.
  const std::string_view named = argc > 1 ? std::string_view(argv[1]) : std::string_view();
  const bool known = std::any_of(std::begin(kBuiltInGroups),
                                 std::end(kBuiltInGroups),
                                 [named](const BuiltInGroup& g) { return g.name == named; }) ||
                     pkm::cli::isRegisteredCommand(named);
  for (const BuiltInGroup& g : kBuiltInGroups)
    if (!known || g.name == named) g.add(app);
  pkm::cli::addRegisteredCommands(app, known ? named : std::string_view());
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
