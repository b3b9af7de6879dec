/// @file
/// @brief The self-contained HTML campaign report (docs/report.md): renders a report-data
/// document (schema `pkm.report/1`) into one HTML file that opens offline, with the plotting
/// library (uPlot, MIT), the client code and the style sheet inlined at build time.
#pragma once

#include <string>
#include <string_view>

namespace pkm::io {

/// The schema tag every report-data document carries in its "schema" key.
inline constexpr std::string_view kReportSchema = "pkm.report/1";

/// Checks a report-data document against schema `pkm.report/1` (docs/report.md): required keys
/// and their types, table rows as long as their columns, plot kinds, unique plot ids, series
/// x/y (or bar categories/y) of equal length, ascending x for line plots.
/// `json_text` is the document as JSON text; `source` names it in syntax errors.
/// Throws pkm::IoError "SOURCE:LINE: invalid JSON: ..." on a syntax error and
/// pkm::InvalidArgument naming the JSON path ("sections[2].plots[0].series[1]: ...") when the
/// document does not follow the schema.
void validateReportData(std::string_view json_text, const std::string& source = "report data");

/// Renders the report-data document `json_text` (validated as by validateReportData, same
/// throws) into one self-contained HTML page: header, summary table, table of contents, sections
/// with their paragraphs, figures and tables. All text is HTML-escaped; the plot data is embedded
/// as JSON with "</" written as "<\/"; no external resource is referenced.
[[nodiscard]] std::string renderHtmlReport(std::string_view json_text,
                                           const std::string& source = "report data");

}  // namespace pkm::io
