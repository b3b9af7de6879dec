/// @file
/// @brief `pkm report render` as a workflow (docs/report.md): a report-data document (schema
/// pkm.report/1) rendered into one self-contained HTML file (io::renderHtmlReport).
#pragma once

#include <cstddef>
#include <string>

#include "pkm/io/named_text.hpp"

namespace pkm::workflow {

/// A report rendering request.
struct ReportRenderRequest {
  io::NamedText data;  ///< the report-data JSON; its name is used in messages (required)
  std::string out;     ///< the HTML file to write (required)
  bool force = false;  ///< replace an existing file
  /// Throws pkm::IoError "give --out FILE" without an output file, and "OUT exists; pass --force
  /// to overwrite it" when it exists and `force` is not set.
  void validate() const;
};

/// What was written.
struct ReportRenderResult {
  std::string out;        ///< the file written
  std::size_t bytes = 0;  ///< its size
};

/// Renders the report and writes it (atomically). Throws as validate(), and pkm::IoError
/// "NAME:LINE: message" for a document that is not valid pkm.report/1 (nothing is written).
[[nodiscard]] ReportRenderResult renderReport(const ReportRenderRequest& request);

}  // namespace pkm::workflow
