// `pkm hexapod ...`: ik, fk, check, describe, hal, linuxcnc-params, machines (docs/formats.md).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <memory>
#include <optional>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "cli_common.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/csv.hpp"
#include "pkm/io/kinematics_csv.hpp"
#include "pkm/io/linuxcnc_hal.hpp"
#include "pkm/io/linuxcnc_hexapod_params.hpp"
#include "pkm/io/machine_description.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/kinematics/hexapod_checks.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "pkm/workflow/hexapod_fk_file.hpp"
#include "pkm/workflow/kinematics_path.hpp"

namespace pkm::cli {

namespace kin = pkm::kinematics;

namespace {

const std::vector<std::string> kPoseColumns = {"x", "y", "z", "a", "b", "c"};
const std::vector<std::string> kLengthColumns = {"l0", "l1", "l2", "l3", "l4", "l5"};

kin::PoseRpy poseFromRow(const std::array<double, 6>& v) {
  kin::PoseRpy p;
  p.position = {v[0], v[1], v[2]};
  p.rpy = {degToRad(v[3]), degToRad(v[4]), degToRad(v[5])};
  return p;
}

kin::PoseRpy parseSeed(const std::string& text) {
  std::array<double, 6> v{};
  std::size_t pos = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    const std::size_t comma = text.find(',', pos);
    if ((comma == std::string::npos) != (i == 5) ||
        !io::parseFiniteDouble(
            std::string_view(text).substr(
                pos, comma == std::string::npos ? std::string::npos : comma - pos),
            v[i]))
      throw IoError(fmt::format("--seed '{}': expected six finite numbers x,y,z,a,b,c", text));
    pos = comma + 1;
  }
  return poseFromRow(v);
}

void runIk(const MachineOption& machine_opt, const std::string& poses) {
  const io::HexapodMachine machine = machine_opt.load();
  kin::HexapodData data(machine.model);
  io::CsvReader reader(poses, kPoseColumns);
  Output out;
  out.text() += "l0,l1,l2,l3,l4,l5,status\n";
  std::array<double, 6> row{};
  while (reader.next(row)) {
    const kin::HexapodCheckResult check = kin::checkPose(machine.model, data, poseFromRow(row));
    for (int i = 0; i < kin::kStruts; ++i) {
      io::appendNumber(out.text(), check.readings[i]);
      out.text() += ',';
    }
    out.text() += check.status();
    out.text() += '\n';
    out.maybeFlush();
  }
}

void runFk(const MachineOption& machine_opt,
           const std::string& lengths,
           const std::string& seed_text,
           bool from_seed) {
  const io::HexapodMachine machine = machine_opt.load();
  workflow::HexapodFkFileRequest request;
  request.lengths = lengths;
  if (!seed_text.empty()) request.seed = parseSeed(seed_text);
  request.from_seed = from_seed;
  Output out;
  (void)workflow::solveHexapodFkFile(
      machine, request, [&out](std::string_view text) { out.write(text); });
  out.flush();
}

void runCheck(const MachineOption& machine_opt, const std::string& poses) {
  const io::HexapodMachine machine = machine_opt.load();
  kin::HexapodData data(machine.model);
  io::CsvReader reader(poses, kPoseColumns);
  Output out;
  out.text() += io::hexapodCheckCsvHeader();
  std::array<double, 6> row{};
  std::size_t index = 0;
  while (reader.next(row)) {
    io::appendHexapodCheckRow(
        out.text(), index++, kin::checkPose(machine.model, data, poseFromRow(row)));
    out.maybeFlush();
  }
}

/// The options of `pkm hexapod`'s subcommands, shared by their callbacks.
struct HexapodCliState {
  MachineOption machine;
  std::string poses, lengths, seed;
  bool json = false;
  std::string kins = "genhexkins";
  bool from_seed = false;
};

/// Adds `pkm hexapod ik`, `fk` and `check` to `hex`.
void addHexapodSolveCommands(CLI::App* hex, const std::shared_ptr<HexapodCliState>& st) {
  CLI::App* ik = hex->add_subcommand(
      "ik", "inverse kinematics: poses x,y,z,a,b,c -> strut readings l0..l5,status");
  st->machine.add(*ik);
  ik->add_option("--poses,-p",
                 st->poses,
                 "CSV with header x,y,z,a,b,c (lengths in the machine unit, degrees); - = stdin")
      ->required();
  ik->callback([st] { runIk(st->machine, st->poses); });

  CLI::App* fk = hex->add_subcommand(
      "fk", "forward kinematics: strut readings l0..l5 -> x,y,z,a,b,c,iterations,status");
  st->machine.add(*fk);
  fk->add_option("--lengths,-l", st->lengths, "CSV with header l0,...,l5 (machine unit); - = stdin")
      ->required();
  fk->add_option(
      "--seed",
      st->seed,
      "first row's seed pose x,y,z,a,b,c (default: home); later rows use the previous solution");
  fk->add_flag("--from-seed",
               st->from_seed,
               "solve every row on its own from the seed (rows that are not a path)");
  fk->callback([st] { runFk(st->machine, st->lengths, st->seed, st->from_seed); });

  CLI::App* check = hex->add_subcommand(
      "check", "per pose: stroke, joint angles, leg interference, conditioning");
  st->machine.add(*check);
  check->add_option("--poses,-p", st->poses, "CSV with header x,y,z,a,b,c; - = stdin")->required();
  check->callback([st] { runCheck(st->machine, st->poses); });
}

/// Adds `pkm hexapod describe`, `hal`, `linuxcnc-params` and `machines` to `hex`.
void addHexapodMachineCommands(CLI::App* hex, const std::shared_ptr<HexapodCliState>& st) {
  CLI::App* describe =
      hex->add_subcommand("describe", "print the machine; --json writes it as a pkm machine file");
  st->machine.add(*describe);
  describe->add_flag("--json", st->json, "write the machine as JSON (docs/machine-format.md)");
  describe->callback([st] {
    const io::HexapodMachine m = st->machine.load();
    Output out;
    if (st->json)
      out.text() += io::writeHexapodJson(m);
    else
      out.text() += io::describeHexapodMachine(m);
  });

  CLI::App* hal = hex->add_subcommand(
      "hal", "write the machine as a LinuxCNC setp block (genhexkins, or pkm's pkmhexkins)");
  st->machine.add(*hal);
  hal->add_option("--kins",
                  st->kins,
                  "kinematics module: genhexkins (LinuxCNC's; joints are joint-centre distances) "
                  "or pkmhexkins (pkm's; joints are the strut readings, all 42 parameters)")
      ->check(CLI::IsMember({"genhexkins", "pkmhexkins"}))
      ->capture_default_str();
  hal->callback([st] {
    Output out;
    const io::HexapodMachine m = st->machine.load();
    out.text() += st->kins == "pkmhexkins" ? io::writePkmhexkinsSetp(m) : io::writeLinuxcncSetp(m);
  });

  CLI::App* params = hex->add_subcommand(
      "linuxcnc-params",
      "write the parameter file of the LinuxCNC kinematics pkmhexkins (loadrt pkmhexkins "
      "params=FILE: read and checked at load)");
  st->machine.add(*params);
  params->callback([st] {
    Output out;
    out.text() += io::linuxcncHexapodParameters(st->machine.load());
  });

  CLI::App* list = hex->add_subcommand("machines", "list the built-in machines");
  list->callback([] {
    for (const auto& n : io::builtinMachineNames()) fmt::print("{}\n", n);
  });
}

}  // namespace

void addHexapodCommands(CLI::App& app) {
  CLI::App* hex = app.add_subcommand("hexapod", "hexapod (6-UPS Stewart platform) kinematics");
  hex->require_subcommand(1);
  auto st = std::make_shared<HexapodCliState>();
  addHexapodSolveCommands(hex, st);
  addHexapodMachineCommands(hex, st);
}

}  // namespace pkm::cli
