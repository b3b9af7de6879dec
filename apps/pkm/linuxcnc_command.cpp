// `pkm linuxcnc install --calibration CAL.json --ini INI [--force]`: a calibrated hexapod written
// into an existing LinuxCNC configuration in place (workflow::installIntoLinuxcnc,
// docs/linuxcnc.md).
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <memory>

#include "cli_common.hpp"
#include "pkm/workflow/linuxcnc_install.hpp"

namespace pkm::cli {
namespace {

void runInstall(const workflow::LinuxcncInstallRequest& request) {
  const workflow::LinuxcncInstallResult r = workflow::installIntoLinuxcnc(request);
  std::size_t values = 0;
  for (const io::TextPatch& p : r.patches) values += p.changes.size();
  if (r.diff.empty()) {
    writeTextOutput("", "the configuration already holds this calibration: nothing to change\n");
    return;
  }
  std::string text = r.diff;
  if (r.written) {
    text += fmt::format("patched {} values; backups: {}\n", values, fmt::join(r.backups, ", "));
    writeTextOutput("", text);
    return;
  }
  writeTextOutput("", text);
  throw InvalidArgument(fmt::format(
      "nothing written: {} values would change (above); pass --force to patch the files in place "
      "(each is first copied to FILE.pkm-backup)",
      values));
}

void addLinuxcnc(CLI::App& app) {
  CLI::App* group = app.add_subcommand("linuxcnc", "work with a LinuxCNC configuration");
  group->require_subcommand(1);
  auto request = std::make_shared<workflow::LinuxcncInstallRequest>();
  CLI::App* install = group->add_subcommand(
      "install",
      "write a calibrated hexapod into an existing configuration in place: the genhexkins setp "
      "values of its kinematics HAL file and the INI's joint HOME, HOME_OFFSET and limits; shows "
      "the differences, writes only with --force, after a backup of each file");
  install->add_option("--calibration", request->calibration, "calibrated hexapod (CAL.json)")
      ->required()
      ->check(CLI::ExistingFile);
  install->add_option("--ini", request->ini, "the configuration's INI file")
      ->required()
      ->check(CLI::ExistingFile);
  install->add_flag("--force", request->force, "patch the files (else only show the differences)");
  install->callback([request] { runInstall(*request); });
}

const CommandRegistration kRegisterLinuxcnc{110, &addLinuxcnc};

}  // namespace
}  // namespace pkm::cli
