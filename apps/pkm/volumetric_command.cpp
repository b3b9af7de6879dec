// `pkm volumetric`: the volumetric error dp of a hybrid machine (seed 000 eq. 3) over a grid of
// tool positions or a list of axis commands, exact and first-order (docs/formats.md).
#include <fmt/format.h>

#include <array>
#include <cmath>
#include <memory>
#include <optional>

#include "cli_common.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/csv.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/kinematics/hybrid_chain.hpp"

namespace pkm::cli {

namespace kin = pkm::kinematics;

namespace {

struct VolumetricState {
  std::string machine = io::kDefaultExechonMachine;
  std::string errors, grid, commands;
  std::optional<double> x2, y2;
};

/// "a:b:n" -> n values from a to b (n = 1: a alone).
std::vector<double> parseAxis(std::string_view text, const std::string& whole) {
  std::array<double, 3> v{};
  std::size_t pos = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    const std::size_t colon = text.find(':', pos);
    const std::string_view field =
        text.substr(pos, colon == std::string_view::npos ? std::string_view::npos : colon - pos);
    if ((colon == std::string_view::npos) != (i == 2) || !io::parseFiniteDouble(field, v[i]))
      throw IoError(fmt::format("--grid '{}': expected X0:X1:NX,Y0:Y1:NY,Z0:Z1:NZ", whole));
    pos = colon + 1;
  }
  if (v[2] < 1 || v[2] > 10000 || v[2] != std::floor(v[2]))
    throw IoError(fmt::format(
        "--grid '{}': the number of points per axis must be an integer in [1, 10000]", whole));
  const auto n = static_cast<int>(v[2]);
  std::vector<double> out;
  for (int k = 0; k < n; ++k) out.push_back(n == 1 ? v[0] : v[0] + (v[1] - v[0]) * k / (n - 1));
  return out;
}

std::array<std::vector<double>, 3> parseGrid(const std::string& text) {
  std::array<std::vector<double>, 3> axes;
  std::size_t pos = 0;
  for (std::size_t a = 0; a < 3; ++a) {
    const std::size_t comma = text.find(',', pos);
    if ((comma == std::string::npos) != (a == 2))
      throw IoError(fmt::format("--grid '{}': expected X0:X1:NX,Y0:Y1:NY,Z0:Z1:NZ", text));
    axes[a] = parseAxis(std::string_view(text).substr(
                            pos, comma == std::string::npos ? std::string::npos : comma - pos),
                        text);
    pos = comma + 1;
  }
  if (axes[0].size() * axes[1].size() * axes[2].size() > 10'000'000)
    throw IoError(fmt::format("--grid '{}': more than 10 million points", text));
  return axes;
}

void appendRow(std::string& o,
               const kin::HybridMachineModel& model,
               const kin::GeometricErrors& errors,
               const kin::HybridCommand& command) {
  const Eigen::Vector3d p = kin::hybridNominalToolPosition(model, command);
  for (int i = 0; i < 3; ++i) o += io::formatNumber(p[i]) + ',';
  o += io::formatNumber(command.x2) + ',' + io::formatNumber(command.y2) + ',';
  for (int i = 0; i < 3; ++i) o += io::formatNumber(command.pkm[i]) + ',';
  Eigen::Vector3d dp, lin;
  try {
    dp = kin::hybridVolumetricError(model, errors, command);
    lin = kin::hybridVolumetricErrorLinear(model, errors, command);
  } catch (
      const InvalidArgument&) {  // a table with "out_of_range": "error" does not cover the command
    o += ",,,,,,,outside_table\n";
    return;
  }
  for (int i = 0; i < 3; ++i) o += io::formatNumber(dp[i]) + ',';
  o += io::formatNumber(dp.norm()) + ',';
  for (int i = 0; i < 3; ++i) o += io::formatNumber(lin[i]) + ',';
  o += kin::hybridWithinLimits(model, command) ? "ok\n" : "axis_limit\n";
}

void runVolumetric(const VolumetricState& st, bool has_grid) {
  const io::ExechonMachine machine = io::loadExechonMachine(st.machine);
  printNotices(machine.notices);
  if (!machine.hybrid)
    throw IoError(
        fmt::format("{}: the machine has no \"hybrid\" section (X2/Y2 axes)", machine.source));
  const kin::HybridMachineModel& model = *machine.hybrid;
  const kin::GeometricErrors errors = io::loadGeometricErrors(st.errors);
  if (errors.unit != model.unit)
    throw IoError(fmt::format("{}: the errors are in {} but the machine {} is in {}",
                              st.errors,
                              toString(errors.unit),
                              machine.source,
                              toString(model.unit)));
  // Check the options and open the input before writing anything.
  std::array<std::vector<double>, 3> axes;
  std::optional<io::CsvReader> reader;
  if (has_grid) {
    if (st.x2.has_value() != st.y2.has_value())
      throw IoError("give both --x2 and --y2, or neither");
    axes = parseGrid(st.grid);
  } else {
    reader.emplace(st.commands, std::vector<std::string>{"x2", "y2", "xp", "yp", "zp"});
  }
  Output out;
  out.text() += "x,y,z,x2,y2,xp,yp,zp,dx,dy,dz,dp,dx_lin,dy_lin,dz_lin,status\n";
  if (has_grid) {
    for (double z : axes[2])
      for (double y : axes[1])
        for (double x : axes[0]) {
          const Eigen::Vector3d p(x, y, z);
          const kin::HybridCommand c = st.x2 ? kin::hybridCommandForTool(model, p, *st.x2, *st.y2)
                                             : kin::hybridCommandCentred(model, p);
          appendRow(out.text(), model, errors, c);
          out.maybeFlush();
        }
    return;
  }
  std::array<double, 5> row{};
  while (reader->next(row)) {
    kin::HybridCommand c;
    c.x2 = row[0];
    c.y2 = row[1];
    c.pkm = {row[2], row[3], row[4]};
    appendRow(out.text(), model, errors, c);
    out.maybeFlush();
  }
}

}  // namespace

void addVolumetricCommand(CLI::App& app) {
  auto st = std::make_shared<VolumetricState>();
  CLI::App* cmd = app.add_subcommand(
      "volumetric",
      "volumetric error dp of a hybrid machine (X2/Y2 + PKM) from its geometric errors");
  cmd->add_option(
      "--machine,-m", st->machine, "machine with a \"hybrid\" section (default: mxt700s-like)");
  cmd->add_option(
         "--errors,-e",
         st->errors,
         "geometric errors: a JSON file (docs/formats.md) or a built-in name (mxt700s-seed000)")
      ->required();
  auto* grid = cmd->add_option(
      "--grid",
      st->grid,
      "X0:X1:NX,Y0:Y1:NY,Z0:Z1:NZ: tool positions in the work frame (machine unit)");
  auto* commands =
      cmd->add_option("--commands", st->commands, "CSV with header x2,y2,xp,yp,zp (axis commands)");
  grid->excludes(commands);
  cmd->add_option("--x2", st->x2, "with --grid: X2 position (default: centred split)");
  cmd->add_option("--y2", st->y2, "with --grid: Y2 position (default: centred split)");
  cmd->callback([st, grid, commands] {
    if (grid->count() == 0 && commands->count() == 0)
      throw CLI::RequiredError("--grid or --commands");
    runVolumetric(*st, grid->count() > 0);
  });
}

}  // namespace pkm::cli
