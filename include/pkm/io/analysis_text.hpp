/// @file
/// @brief The tables `pkm analyze <kind>` prints without --json (docs/analysis.md): one text per
/// report of io/analysis_report.hpp, returned whole (lines end in '\n'). Positioning and circle
/// tables are tab-separated with numbers to 6 and 9 significant digits ("-" when not finite);
/// diagonal tables are CSV with the shortest round-trip numbers and "# key,value" lines.
#pragma once

#include <string>

#include "pkm/io/analysis_report.hpp"

namespace pkm::io {

/// The table of each analysis report.
[[nodiscard]] std::string analysisText(const Iso230_2Report& report);
[[nodiscard]] std::string analysisText(const StraightnessReport& report);
[[nodiscard]] std::string analysisText(const ParallelismReport& report);
[[nodiscard]] std::string analysisText(const SquarenessReport& report);
/// Step and shifted: the "# compare" lines come first, then the table.
[[nodiscard]] std::string analysisText(const DiagonalsReport& report);
[[nodiscard]] std::string analysisText(const CircleReport& report);
[[nodiscard]] std::string analysisText(const CircularReport& report);
[[nodiscard]] std::string analysisText(const ProbeOffsetReport& report);

}  // namespace pkm::io
