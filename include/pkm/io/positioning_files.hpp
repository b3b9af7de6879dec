/// @file
/// @brief Readers of positioning and straightness measurement files, from memory (io::NamedText),
/// shared by `pkm analyze` and `pkm compensate` (docs/analysis.md, "ISO 230-2 positioning" and
/// "Straightness"; docs/formats.md, "Measurement files"). Errors name the input and the line,
/// "NAME:LINE: message", whether it came from a file or an upload.
#pragma once

#include <span>
#include <vector>

#include "pkm/io/named_text.hpp"
#include "pkm/io/text_table.hpp"
#include "pkm/metrology/iso230_2.hpp"

namespace pkm::io {

/// True for a simulator measurement file (docs/formats.md "Measurement files"): it has the
/// columns target_mm and reading_mm.
[[nodiscard]] bool isMeasurementFile(const TextTable& t);

/// Points (position, value) along a line, e.g. per-target means; both in the file's length unit.
struct Profile {
  std::vector<double> position, value;
};

/// Per-target mean of the readings of simulator measurement files (over runs and directions;
/// rows with a sub_step other than 0 left out; metrology::perTargetMeans), sorted by target;
/// `minus_target` subtracts the target (the positioning deviation). Throws pkm::IoError
/// "NAME:LINE: message" for a missing column or a bad field.
[[nodiscard]] Profile meanProfile(std::span<const TextTable> tables, bool minus_target);

/// Points (position, deviation) from plain `position,deviation` inputs (concatenated, in input
/// order) followed by the per-target means of simulator straightness files (meanProfile).
/// Throws pkm::IoError "NAME:LINE: message".
[[nodiscard]] Profile readStraightness(std::span<const NamedText> inputs);

/// ISO 230-2 samples (ISO 230-2:2014 §2) from `target,direction,run,measured` inputs or simulator
/// linear files (`target_mm`, `reading_mm`), concatenated. Throws pkm::IoError
/// "NAME:LINE: message" for a bad field, a run < 1 or a repeated (target, direction, run)
/// ("... (first at NAME:LINE)").
[[nodiscard]] std::vector<metrology::PositioningSample> readPositioningSamples(
    std::span<const NamedText> inputs);

}  // namespace pkm::io
