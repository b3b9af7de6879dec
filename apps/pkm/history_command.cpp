// `pkm history --machine NAME [--db pkm.db]`: how a machine's results evolve across campaigns
// (the result store, pkm/store/result_store.hpp; docs/formats.md, "Result store").
#include <memory>

#include "cli_common.hpp"
#include "pkm/store/history_report.hpp"
#include "pkm/workflow/history.hpp"

namespace pkm::cli {
namespace {

struct HistoryArgs {
  workflow::HistoryRequest request;
  bool json = false;
};

void runHistory(HistoryArgs& args) {
  args.request.require_rows = !args.json;
  const workflow::HistoryResult r = workflow::queryHistory(args.request);
  writeTextOutput(
      "", args.json ? store::historyJson(r.machine, r.db, r.rows) : store::historyText(r.rows));
}

void addHistory(CLI::App& app) {
  auto args = std::make_shared<HistoryArgs>();
  CLI::App* cmd =
      app.add_subcommand("history", "a machine's results across campaigns (the result store)");
  cmd->add_option("--machine", args->request.machine, "machine name")->required();
  cmd->add_option("--db", args->request.db, "result store")->capture_default_str();
  cmd->add_option("--quantity", args->request.quantity, "only this quantity (e.g. holdout.rms)");
  cmd->add_flag("--json", args->json, "print JSON");
  cmd->callback([args] { runHistory(*args); });
}

const CommandRegistration kRegisterHistory{100, "history", &addHistory};

}  // namespace
}  // namespace pkm::cli
