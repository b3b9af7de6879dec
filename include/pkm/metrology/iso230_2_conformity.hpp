/// @file
/// @brief The ISO 230-2:2014 test conditions a positioning data set is checked against before its
/// figures are reported as ISO 230-2 figures (docs/analysis.md, "ISO 230-2 positioning"): the
/// standard test cycle (§ 6.2: every target approached 5 times from each direction) and the
/// target density (§ 5.2: at least five targets per metre and five in all on an axis up to
/// 2000 mm; about 250 mm apart on a longer axis, measured in one run per direction). A data set
/// that misses them is still evaluated, and flagged.
#pragma once

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pkm/metrology/iso230_2.hpp"

namespace pkm::metrology {

/// Runs of the standard test cycle per direction at every target (ISO 230-2:2014, 6.2).
inline constexpr int kIso230_2Runs = 5;
/// Targets per metre of travel, and in all, on an axis up to kIso230_2LongAxis (5.2).
inline constexpr double kIso230_2TargetsPerMetre = 5.0;
inline constexpr int kIso230_2MinTargets = 5;
/// Travel above which an axis is "long", mm, and the largest average target spacing there, mm.
inline constexpr double kIso230_2LongAxis = 2000.0;
inline constexpr double kIso230_2LongAxisSpacing = 250.0;

/// The conditions `samples` do not meet, one sentence each (empty: the data conform): one
/// direction only; fewer than kIso230_2Runs runs in a direction (axes up to 2000 mm); run counts
/// that differ between targets (an incomplete run, naming the first such target); too few
/// targets for the travel; too wide a spacing on a long axis. `millimetres_per_unit` converts the
/// targets' unit to mm (the density rules are in mm). Precondition: samples not empty,
/// millimetres_per_unit > 0 (pkm::InvalidArgument otherwise).
[[nodiscard]] std::vector<std::string> iso230_2Nonconformities(
    std::span<const PositioningSample> samples, double millimetres_per_unit = 1.0);

/// The largest plausible positioning deviation, as a fraction of the travel: 10 mm on a metre is
/// far beyond any machine axis, while deviations in µm read as mm, or a deviation column read as
/// measured positions, give deviations of the order of the travel itself.
inline constexpr double kPlausibleDeviationFraction = 0.01;

/// Plausibility warnings (empty when none): deviations |measured − target| larger than
/// kPlausibleDeviationFraction of the travel, naming the likely causes. `unit` names the
/// samples' unit in the message. Precondition: samples not empty.
[[nodiscard]] std::vector<std::string> implausibleDeviations(
    std::span<const PositioningSample> samples, std::string_view unit = "mm");

}  // namespace pkm::metrology
