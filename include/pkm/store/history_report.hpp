/// @file
/// @brief A machine's history from the result store (`pkm history`, docs/formats.md "Result
/// store") as the text table and as the `--json` document.
#pragma once

#include <string>
#include <vector>

#include "pkm/store/result_store.hpp"

namespace pkm::store {

/// The rows as a table with a header line: campaign, time, campaign name, quantity, stage,
/// "value ± U" (6 and 2 significant digits; the value alone where there is no U), unit, in
/// aligned columns.
[[nodiscard]] std::string historyText(const std::vector<HistoryRow>& rows);

/// The history as one JSON object (two-space indent, closing newline): machine, db and rows
/// (campaign, time, campaign_name, quantity, stage, value, U (k = 2; null when none), unit).
[[nodiscard]] std::string historyJson(const std::string& machine,
                                      const std::string& db,
                                      const std::vector<HistoryRow>& rows);

}  // namespace pkm::store
