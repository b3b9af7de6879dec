/// @file
/// @brief Internal: the parsed and validated report-data document (schema pkm.report/1) shared by
/// the HTML report's validator and renderer (pkm/io/html_report.hpp).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace pkm::io::detail {

/// Parses `json_text` (pkm::IoError "SOURCE:LINE: invalid JSON" on a syntax error) and checks it
/// against pkm.report/1 (pkm::InvalidArgument naming the JSON path). Returns the document.
[[nodiscard]] nlohmann::json parseReportData(std::string_view json_text, const std::string& source);

}  // namespace pkm::io::detail
