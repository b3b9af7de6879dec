/// @file
/// @brief Renishaw LaserXL `.rtl` linear-measurement text files (docs/formats.md, "Instrument
/// exports"): sections opened by `NAME::` lines; `Targets :` (mm) in TARGET DATA; under
/// DEVIATIONS, after `Run Target Data:`, rows `run target-index deviation` (µm). Renishaw
/// publishes no specification: the layout is the one independent public readers of these files
/// agree on, and the reader checks what it relies on (target count, indices, one direction per
/// run) instead of guessing.
#pragma once

#include <string_view>
#include <vector>

#include "pkm/io/named_text.hpp"
#include "pkm/metrology/iso230_2.hpp"

namespace pkm::io {

/// True when `text` looks like an `.rtl` file: its first non-blank line is a `NAME::` section
/// line and it has a `DEVIATIONS::` section.
[[nodiscard]] bool isRenishawRtl(std::string_view text);

/// The ISO 230-2 samples of an `.rtl` file, in mm. A run's direction is the order in which it
/// visits the targets (ascending: +, descending: −; a run of one target alternates, odd runs +);
/// runs are numbered 1, 2, … per direction in file order. Throws pkm::IoError "NAME:LINE:
/// message" for a missing section or key, a target count that disagrees with `Target-count`, a
/// target index outside 1…count, a run that visits targets in both orders, a repeated (run,
/// target) or a field that is not a number.
[[nodiscard]] std::vector<metrology::PositioningSample> readRenishawRtl(const NamedText& input);

}  // namespace pkm::io
