// `pkm compensate table`: controller compensation tables (LinuxCNC COMP_FILE type 0/1, SINUMERIK
// 840D EEC and CEC part programs, ISG CSV) from ISO 230-2 positioning or straightness files
// (docs/compensation.md).
#include <memory>
#include <string>
#include <vector>

#include "analyze_common.hpp"
#include "cli_common.hpp"
#include "pkm/io/compensation_table_report.hpp"
#include "pkm/workflow/compensation_table.hpp"

namespace pkm::cli {
namespace {

struct TableState {
  workflow::CompensationTableRequest request;
  std::vector<std::string> data;
  PositioningColumnArgs columns;
  bool json = false;
};

void runTable(TableState& st) {
  st.request.data = io::readNamedTexts(st.data);
  st.request.columns = st.columns.parsed();
  st.request.machine = st.columns.machine;
  st.request.ini = st.columns.ini;
  CliRunControl run;
  const workflow::CompensationTableResult r =
      workflow::writeCompensationTable(st.request, run.control());
  run.finish();
  writeTextOutput(
      "", st.json ? io::compensationTableJson(r.summary) : io::compensationTableText(r.summary));
}

void addCompensateCommand(CLI::App& app) {
  CLI::App* compensate = app.add_subcommand(
      "compensate", "controller compensation tables from measurements (docs/compensation.md)");
  compensate->require_subcommand(1);
  auto st = std::make_shared<TableState>();
  CLI::App* cmd = compensate->add_subcommand(
      "table",
      "write an axis error table for a controller from ISO 230-2 positioning files (or "
      "straightness files for siemens-cec / isg with --output-axis)");
  cmd->add_option("--data", st->data, "measurement file(s): as pkm analyze iso230-2 / straightness")
      ->required()
      ->expected(1, CLI::detail::expected_max_vector_size)
      ->check(CLI::ExistingFile);
  cmd->add_option(
         "--format", st->request.format, "linuxcnc0, linuxcnc1, siemens-eec, siemens-cec or isg")
      ->required()
      ->check(CLI::IsMember({"linuxcnc0", "linuxcnc1", "siemens-eec", "siemens-cec", "isg"}));
  cmd->add_option(
      "--axis", st->request.axis, "axis name as the controller knows it (X, X1, AX1, ...)");
  cmd->add_option("--input-axis", st->request.input_axis, "straightness: the base axis (argument)");
  cmd->add_option("--output-axis", st->request.output_axis, "straightness: the compensated axis");
  cmd->add_option("--line",
                  st->request.line,
                  "straightness: reference line removed first: endpoint (default), lsq or raw")
      ->check(CLI::IsMember({"endpoint", "lsq", "raw"}));
  st->columns.add(*cmd);
  cmd->add_option("--out,-o", st->request.out, "output file")->required();
  cmd->add_flag("--force", st->request.force, "overwrite an existing output file");
  cmd->add_option("--max-points",
                  st->request.max_points,
                  "most rows (default: linuxcnc 256, siemens 200, isg 1500); longer tables are "
                  "resampled evenly")
      ->check(CLI::Range(2, 1'000'000));
  cmd->add_option("--encoder", st->request.encoder, "siemens-eec: measuring system 0 or 1")
      ->check(CLI::IsMember({0, 1}));
  cmd->add_option("--table", st->request.table_index, "siemens-cec: table index t (default 0)")
      ->check(CLI::Range(0, 1000));
  cmd->add_flag("--json", st->json, "print one JSON object instead of the summary");
  cmd->callback([st] { runTable(*st); });
}

const CommandRegistration kRegisterCompensate{50, "compensate", &addCompensateCommand};

}  // namespace
}  // namespace pkm::cli
