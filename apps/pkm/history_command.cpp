// `pkm history --machine NAME [--db pkm.db]`: how a machine's results evolve across campaigns
// (the result store, pkm/io/result_store.hpp; docs/formats.md, "Result store").
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "analyze_common.hpp"
#include "cli_common.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/result_store.hpp"

namespace pkm::cli {
namespace {

struct HistoryArgs {
  std::string machine;
  std::string db = "pkm.db";
  std::string quantity;
  bool json = false;
};

void runHistory(const HistoryArgs& args) {
  // Reading never creates a store.
  if (!std::filesystem::exists(args.db))
    throw IoError(fmt::format("{}: no result store (campaigns and `--db` write one)", args.db));
  io::ResultStore store(args.db);
  std::optional<std::string> quantity;
  if (!args.quantity.empty()) quantity = args.quantity;
  const std::vector<io::HistoryRow> rows = store.history(args.machine, quantity);
  if (args.json) {
    nlohmann::ordered_json j;
    j["machine"] = args.machine;
    j["db"] = args.db;
    j["rows"] = nlohmann::ordered_json::array();
    for (const io::HistoryRow& r : rows)
      j["rows"].push_back({{"campaign", r.campaign},
                           {"time", r.time},
                           {"campaign_name", r.campaign_name},
                           {"quantity", r.quantity},
                           {"stage", r.stage},
                           {"value", r.value},
                           {"unit", r.unit}});
    printJson(j);
    return;
  }
  if (rows.empty()) {
    const std::vector<std::string> known = store.machines();
    throw InvalidArgument(
        fmt::format("{}: no results for machine '{}' (machines in the store: {})",
                    args.db,
                    args.machine,
                    known.empty() ? "none" : fmt::format("{}", fmt::join(known, ", "))));
  }
  Output out;
  std::string& t = out.text();
  t += fmt::format("{:>8}  {:<20}  {:<24}  {:<28}  {:<10}  {:>14}  {}\n",
                   "campaign",
                   "time",
                   "campaign name",
                   "quantity",
                   "stage",
                   "value",
                   "unit");
  for (const io::HistoryRow& r : rows)
    t += fmt::format("{:>8}  {:<20}  {:<24}  {:<28}  {:<10}  {:>14.6g}  {}\n",
                     r.campaign,
                     r.time,
                     r.campaign_name,
                     r.quantity,
                     r.stage,
                     r.value,
                     r.unit);
}

void addHistory(CLI::App& app) {
  auto args = std::make_shared<HistoryArgs>();
  CLI::App* cmd =
      app.add_subcommand("history", "a machine's results across campaigns (the result store)");
  cmd->add_option("--machine", args->machine, "machine name")->required();
  cmd->add_option("--db", args->db, "result store")->capture_default_str();
  cmd->add_option("--quantity", args->quantity, "only this quantity (e.g. holdout.rms)");
  cmd->add_flag("--json", args->json, "print JSON");
  cmd->callback([args] { runHistory(*args); });
}

const CommandRegistration kRegisterHistory{100, &addHistory};

}  // namespace
}  // namespace pkm::cli
