// A machine's history as text and JSON (history_report.hpp).
#include "pkm/store/history_report.hpp"

#include <fmt/format.h>

#include <cmath>
#include <nlohmann/json.hpp>

namespace pkm::store {

namespace {

/// "VALUE ± U" (6 and 2 significant digits), "VALUE" without U.
std::string valueWithU(const HistoryRow& r) {
  if (std::isnan(r.U)) return fmt::format("{:.6g}", r.value);
  return fmt::format("{:.6g} ± {:.2g}", r.value, r.U);
}

}  // namespace

std::string historyText(const std::vector<HistoryRow>& rows) {
  std::string t = fmt::format("{:>8}  {:<20}  {:<24}  {:<28}  {:<10}  {:>24}  {}\n",
                              "campaign",
                              "time",
                              "campaign name",
                              "quantity",
                              "stage",
                              "value ± U (k = 2)",
                              "unit");
  for (const HistoryRow& r : rows)
    t += fmt::format("{:>8}  {:<20}  {:<24}  {:<28}  {:<10}  {:>24}  {}\n",
                     r.campaign,
                     r.time,
                     r.campaign_name,
                     r.quantity,
                     r.stage,
                     valueWithU(r),
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
    j["rows"].push_back(
        {{"campaign", r.campaign},
         {"time", r.time},
         {"campaign_name", r.campaign_name},
         {"quantity", r.quantity},
         {"stage", r.stage},
         {"value", r.value},
         {"U", std::isnan(r.U) ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(r.U)},
         {"unit", r.unit}});
  return j.dump(2) + "\n";
}

}  // namespace pkm::store
