// A machine's history as text and JSON (history_report.hpp).
#include "pkm/io/history_report.hpp"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

namespace pkm::io {

std::string historyText(const std::vector<HistoryRow>& rows) {
  std::string t = fmt::format("{:>8}  {:<20}  {:<24}  {:<28}  {:<10}  {:>14}  {}\n",
                              "campaign",
                              "time",
                              "campaign name",
                              "quantity",
                              "stage",
                              "value",
                              "unit");
  for (const HistoryRow& r : rows)
    t += fmt::format("{:>8}  {:<20}  {:<24}  {:<28}  {:<10}  {:>14.6g}  {}\n",
                     r.campaign,
                     r.time,
                     r.campaign_name,
                     r.quantity,
                     r.stage,
                     r.value,
                     r.unit);
  return t;
}

std::string historyJson(const std::string& machine,
                        const std::string& db,
                        const std::vector<HistoryRow>& rows) {
  nlohmann::ordered_json j;
  j["machine"] = machine;
  j["db"] = db;
  j["rows"] = nlohmann::ordered_json::array();
  for (const HistoryRow& r : rows)
    j["rows"].push_back({{"campaign", r.campaign},
                         {"time", r.time},
                         {"campaign_name", r.campaign_name},
                         {"quantity", r.quantity},
                         {"stage", r.stage},
                         {"value", r.value},
                         {"unit", r.unit}});
  return j.dump(2) + "\n";
}

}  // namespace pkm::io
