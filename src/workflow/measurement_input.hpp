// Internal: positioning and straightness measurement files read from memory (docs/formats.md,
// "Measurement files"; docs/analysis.md, "ISO 230-2 positioning" and "Straightness").
#pragma once

#include <vector>

#include "pkm/io/named_text.hpp"
#include "pkm/metrology/iso230_2.hpp"

namespace pkm::workflow::detail {

/// Points (position, value), e.g. per-target means.
struct Profile {
  std::vector<double> position, value;
};

/// Points (position, deviation) from plain `position,deviation` files (concatenated) or simulator
/// straightness files (`target_mm`, `reading_mm`; averaged per target, sub_step 0 only). Throws
/// pkm::IoError "NAME:LINE: message".
[[nodiscard]] Profile readStraightness(const std::vector<io::NamedText>& files);

/// ISO 230-2 samples from `target,direction,run,measured` files or simulator linear files
/// (`target_mm`, `reading_mm`), concatenated. Throws pkm::IoError "NAME:LINE: message" for a bad
/// field, a run < 1 or a repeated (target, direction, run) ("... (first at NAME:LINE)").
[[nodiscard]] std::vector<metrology::PositioningSample> readPositioningSamples(
    const std::vector<io::NamedText>& files);

}  // namespace pkm::workflow::detail
