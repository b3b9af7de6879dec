/// @file
/// @brief Readers of positioning and straightness measurement files shared by `pkm analyze` and
/// `pkm compensate` (docs/analysis.md, "ISO 230-2 positioning" and "Straightness";
/// docs/formats.md, "Measurement files").
#pragma once

#include <string>
#include <vector>

#include "pkm/io/text_table.hpp"
#include "pkm/metrology/iso230_2.hpp"

namespace pkm::cli {

/// A simulator measurement file (docs/formats.md "Measurement files"): target_mm and reading_mm.
[[nodiscard]] bool isMeasurementFile(const io::TextTable& t);

/// Points (position, value), e.g. per-target means.
struct Profile {
  std::vector<double> position, value;
};

/// Per-target mean of the readings of simulator files (over runs and directions; rows with a
/// sub_step other than 0 left out; metrology::perTargetMeans), sorted by target; `minus_target`
/// subtracts the target (positioning deviation).
[[nodiscard]] Profile meanProfile(const std::vector<io::TextTable>& tables, bool minus_target);

/// Points (position, deviation) from plain `position,deviation` files (concatenated) or simulator
/// straightness files (averaged per target). Throws pkm::IoError "FILE:LINE: message".
[[nodiscard]] Profile readStraightness(const std::vector<std::string>& files);

/// ISO 230-2 samples from `target,direction,run,measured` files or simulator linear files
/// (`target_mm`, `reading_mm`), concatenated. Throws pkm::IoError "FILE:LINE: message" for a bad
/// field, a run < 1 or a repeated (target, direction, run) ("... (first at FILE:LINE)").
[[nodiscard]] std::vector<metrology::PositioningSample> readPositioningSamples(
    const std::vector<std::string>& files);

}  // namespace pkm::cli
