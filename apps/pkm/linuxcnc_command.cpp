// `pkm linuxcnc install --calibration CAL.json --ini INI [--force]`: a calibrated hexapod written
// into an existing LinuxCNC configuration in place (workflow::installIntoLinuxcnc), and
// `pkm linuxcnc config --machine M --out DIR [--comp-file JOINT=FILE ...] [--force]`: a complete
// configuration (workflow::writeLinuxcncConfig); docs/linuxcnc.md.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>
#include <memory>

#include "cli_common.hpp"
#include "pkm/workflow/linuxcnc_config.hpp"
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

/// "JOINT=FILE" of --comp-file.
workflow::LinuxcncCompInput parseCompFile(const std::string& text) {
  const std::size_t eq = text.find('=');
  int joint = -1;
  if (eq != std::string::npos && eq > 0 && eq + 1 < text.size()) {
    const std::string index = text.substr(0, eq);
    if (index.find_first_not_of("0123456789") == std::string::npos && index.size() < 3)
      joint = std::stoi(index);
  }
  if (joint < 0)
    throw InvalidArgument(
        fmt::format("--comp-file/--comp-data '{}': give JOINT=FILE, e.g. 0=strut0.comp", text));
  return {joint, text.substr(eq + 1)};
}

void runConfig(workflow::LinuxcncConfigRequest request,
               const std::vector<std::string>& comp,
               const std::vector<std::string>& data) {
  for (const std::string& c : comp) request.comp_files.push_back(parseCompFile(c));
  for (const std::string& d : data) request.comp_data.push_back(parseCompFile(d));
  const workflow::LinuxcncConfigResult r = workflow::writeLinuxcncConfig(request);
  printNotices(r.notices);
  std::string text = fmt::format("wrote a LinuxCNC {} configuration:\n", r.kind);
  for (const std::string& f : r.files) text += fmt::format("  {}\n", f);
  text += fmt::format(
      "run it with: linuxcnc {}\n(the kinematics module, {}.so, must be in LinuxCNC's module "
      "folder: docs/linuxcnc.md)\n",
      r.ini,
      r.kind == "exechon" ? "pkmexechonkins" : "pkmhexkins");
  writeTextOutput("", text);
}

void addConfig(CLI::App& group) {
  struct State {
    workflow::LinuxcncConfigRequest request;
    std::vector<std::string> comp;
    std::vector<std::string> data;
  };
  auto st = std::make_shared<State>();
  CLI::App* config = group.add_subcommand(
      "config",
      "write a complete LinuxCNC configuration for a machine on LinuxCNC's simulator: the INI, "
      "the kinematics HAL file (pkmhexkins or pkmexechonkins), a simulator HAL file, a tool "
      "table, an Exechon's parameter file and the given joint compensation tables; world "
      "coordinates are those `pkm hexapod fk` / `pkm exechon fk` report, and after homing the "
      "machine stands at its home pose");
  config
      ->add_option("--machine,-m",
                   st->request.machine,
                   "hexapod JSON (also CAL.json of pkm calibrate hexapod), LinuxCNC .hal, Exechon "
                   "JSON, or a built-in name (default: the default hexapod)")
      ->capture_default_str();
  config->add_option(
      "--ini", st->request.ini, "LinuxCNC INI file of a .hal machine (else the one beside it)");
  config->add_option("--out,-o", st->request.out, "the configuration folder (created)")->required();
  config->add_option("--comp-file",
                     st->comp,
                     "JOINT=FILE: a compensation table of that joint (pkm compensate table "
                     "--format linuxcnc0|linuxcnc1), copied as jointN.comp; repeat per joint");
  config->add_option("--comp-data",
                     st->data,
                     "JOINT=FILE: the ISO 230-2 positioning data (mm) that joint's table was made "
                     "from: a table whose corrections have the errors' sign is refused");
  config
      ->add_option("--comp-file-type",
                   st->request.comp_file_type,
                   "COMP_FILE_TYPE of the tables: 0 (linuxcnc0) or 1 (linuxcnc1)")
      ->check(CLI::IsMember({0, 1}));
  config
      ->add_option("--display",
                   st->request.display,
                   "[DISPLAY] DISPLAY: axis (LinuxCNC's GUI) or linuxcncrsh (headless, telnet "
                   "port 5007)")
      ->capture_default_str();
  config->add_option("--simulate-truth",
                     st->request.simulate_truth,
                     "TRUTH.json of `pkm simulate` (a hexapod in mm): add the simulated physical "
                     "machine to the loop (pkm-truth: true struts, three dial gauges and a laser "
                     "along x as HAL pins; docs/linuxcnc.md)");
  config->add_flag("--force", st->request.force, "replace files of the same names in the folder");
  config->add_flag_callback(
      "--no-comp-check",
      [st] { st->request.check_comp_files = false; },
      "use the --comp-file tables even when a correction is larger than 1 % of the joint's travel "
      "(a table of the wrong type or unit is refused without it); their format is still checked");
  config->callback([st] {
    const std::filesystem::path truth = programDirectory() / "pkm-truth";
    if (std::filesystem::exists(truth)) st->request.truth_program = truth.string();
    runConfig(st->request, st->comp, st->data);
  });
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
  addConfig(*group);
}

const CommandRegistration kRegisterLinuxcnc{110, "linuxcnc", &addLinuxcnc};

}  // namespace
}  // namespace pkm::cli
