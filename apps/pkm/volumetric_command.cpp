// `pkm volumetric`: the volumetric error dp of a hybrid machine (MXT700S parallelism paper, eq. 3)
// over a grid of tool positions or a list of axis commands, exact and first-order
// (docs/formats.md).
#include <memory>

#include "cli_common.hpp"
#include "pkm/workflow/volumetric.hpp"

namespace pkm::cli {

namespace {

struct VolumetricState {
  workflow::VolumetricRequest request;
  std::string grid, commands;
};

void runVolumetric(VolumetricState& st, bool has_grid) {
  if (has_grid)
    st.request.grid = st.grid;
  else
    st.request.commands = readCsvInput(st.commands);
  CliRunControl run;
  Output out;
  workflow::VolumetricSink sink;
  sink.begin = [&out] { out.text() += io::volumetricCsvHeader(); };
  sink.row = [&out](const io::VolumetricRow& row) {
    io::appendVolumetricCsvRow(out.text(), row);
    out.maybeFlush();
  };
  static_cast<void>(workflow::computeVolumetricErrors(st.request, sink, run.control()));
}

}  // namespace

void addVolumetricCommand(CLI::App& app) {
  auto st = std::make_shared<VolumetricState>();
  CLI::App* cmd = app.add_subcommand(
      "volumetric",
      "volumetric error dp of a hybrid machine (X2/Y2 + PKM) from its geometric errors");
  cmd->add_option("--machine,-m",
                  st->request.machine,
                  "machine with a \"hybrid\" section (default: mxt700s-like)");
  cmd->add_option(
         "--errors,-e",
         st->request.errors,
         "geometric errors: a JSON file (docs/formats.md) or a built-in name (mxt700s-seed000)")
      ->required();
  auto* grid = cmd->add_option(
      "--grid",
      st->grid,
      "X0:X1:NX,Y0:Y1:NY,Z0:Z1:NZ: tool positions in the work frame (machine unit)");
  auto* commands =
      cmd->add_option("--commands", st->commands, "CSV with header x2,y2,xp,yp,zp (axis commands)");
  grid->excludes(commands);
  cmd->add_option("--x2", st->request.x2, "with --grid: X2 position (default: centred split)");
  cmd->add_option("--y2", st->request.y2, "with --grid: Y2 position (default: centred split)");
  cmd->callback([st, grid, commands] {
    if (grid->count() == 0 && commands->count() == 0)
      throw CLI::RequiredError("--grid or --commands");
    runVolumetric(*st, grid->count() > 0);
  });
}

}  // namespace pkm::cli
