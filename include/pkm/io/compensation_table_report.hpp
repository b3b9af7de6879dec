/// @file
/// @brief The summary of a controller compensation table (`pkm compensate table`,
/// docs/compensation.md): what was written, its size and range, and the largest correction, as
/// the text summary and as the `--json` document.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace pkm::io {

/// A compensation table, as reported.
struct CompensationTableSummary {
  std::string format;                     ///< linuxcnc0, linuxcnc1, siemens-eec, siemens-cec or isg
  std::string out;                        ///< the file written
  std::string axis;                       ///< the compensated axis
  std::optional<std::string> input_axis;  ///< straightness tables: the base axis
  std::size_t rows = 0;                   ///< rows of the table written
  std::size_t input_rows = 0;             ///< rows before fitting to the format (resampling)
  std::string unit = "mm";                ///< the table's length unit, and the figures' below
  double first = 0.0, last = 0.0;         ///< the first and last nominal position
  double max_correction = 0.0;  ///< largest |stored correction|, as the controller applies it
  /// ISO 230-2 figures of positioning data: bidirectional systematic deviation E, reversal B and
  /// mean bidirectional positional deviation M (ISO 230-2:2014, 3.3).
  struct Iso {
    double E = 0.0, B = 0.0, M = 0.0;
  };
  std::optional<Iso> iso;  ///< positioning tables only
};

/// The summary as text: "compensation table (FORMAT, axis A[ over B])", then tab-separated rows,
/// range, max_correction, measured E (when finite; with the unit) and wrote.
[[nodiscard]] std::string compensationTableText(const CompensationTableSummary& summary);

/// The summary as one JSON object (two-space indent, closing newline): format, out, axis, rows,
/// input_rows, unit, first, last, max_correction, and input_axis, E, B, M when present.
[[nodiscard]] std::string compensationTableJson(const CompensationTableSummary& summary);

}  // namespace pkm::io
