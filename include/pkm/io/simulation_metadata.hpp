/// @file
/// @brief The "# key: value" metadata of simulated line-measurement and dial-gauge files
/// (docs/formats.md, "Measurement files"): what `pkm simulate` and the campaign write above
/// the rows, and what the campaign's file readers rebuild a set-up from.
#pragma once

#include <cstdint>

#include "pkm/io/scenario.hpp"
#include "pkm/io/text_table.hpp"
#include "pkm/simulation/dial_gauges.hpp"
#include "pkm/simulation/line_measurement.hpp"

namespace pkm::io {

/// The metadata of run `run` of line measurement `setup` of `scenario` simulated with `seed`:
/// format, scenario, seed, measurement, quantity, instrument, procedure, run, axes, line start and
/// direction (angular axes in degrees), reflector offset, noise, and lateral / misalignment where
/// they apply. A linear line in an environment with a set-up also gets the records its budget
/// uses (docs/formats.md, "Environment records"): dead path, beam alignment and, from `runs`
/// (the line's readings, their rotations recorded), the Abbe offset bound and the angular range.
[[nodiscard]] Metadata lineRunMetadata(const Scenario& scenario,
                                       std::uint64_t seed,
                                       const simulation::LineSetup& setup,
                                       int run,
                                       const std::vector<simulation::LineRun>& runs = {});

/// The set-up part of a constrained-motion file's metadata (what io::readConstrainedMotionCsv
/// reads): `format`, `instrument` (as given), `gauge points mm`, `table normal`, `tolerance mm`.
[[nodiscard]] Metadata gaugeSetupMetadata(const simulation::DialGaugeSetup& setup,
                                          const std::string& instrument);

/// The metadata of the dial-gauge file of constrained-motion set-up `setup`.
[[nodiscard]] Metadata dialGaugeMetadata(const Scenario& scenario,
                                         std::uint64_t seed,
                                         const simulation::DialGaugeSetup& setup);

}  // namespace pkm::io
