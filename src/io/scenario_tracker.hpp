/// @file
/// @brief Internal: the laser-tracker measurements and the Cartesian actuation of a scenario
/// (docs/formats.md, "Scenario files"), and their part of truth.json.
#pragma once

#include <string>

#include "io/detail/json_doc.hpp"
#include "pkm/simulation/campaign.hpp"
#include "pkm/simulation/cartesian_machine.hpp"

namespace pkm::io::detail {

/// A laser-tracker measurement on an Exechon ("instrument": "laser_tracker" on a "hybrid"
/// machine) at `ptr`: count, box {x, y, z: [min, max] mm}, direction, max_tilt_deg, smr_offset,
/// tracker_frame, noise. Fails through `doc`.
[[nodiscard]] simulation::ExechonTrackerSetup readExechonTracker(const JsonDoc& doc,
                                                                 const json& obj,
                                                                 const std::string& ptr);

/// A laser-tracker measurement of a hybrid machine's tool over its five axes ("instrument":
/// "laser_tracker", "mode": "hybrid" on a "hybrid" machine) at `ptr`: count, x2, y2 ([min, max]
/// mm), box {x, y, z} (PKM command), smr_offset, tracker_frame (in the work frame), noise.
[[nodiscard]] simulation::HybridTrackerSetup readHybridTracker(const JsonDoc& doc,
                                                               const json& obj,
                                                               const std::string& ptr);

/// A laser-tracker measurement ("instrument": "laser_tracker") at `ptr`. Fails through `doc`.
[[nodiscard]] simulation::TrackerSetup readTracker(const JsonDoc& doc,
                                                   const json& obj,
                                                   const std::string& ptr);

/// A Cartesian machine's "actuation" object at `ptr`: "backlash" and "repeatability_sigma", each
/// one number (mm) or [x, y, z]. Fails through `doc`.
[[nodiscard]] simulation::CartesianActuation readCartesianActuation(const JsonDoc& doc,
                                                                    const json& obj,
                                                                    const std::string& ptr);

/// The truth.json members for the laser trackers and a Cartesian machine's actuation, each
/// starting with ",\n  " (empty when there are none), to go before the closing brace.
[[nodiscard]] std::string extraTruthJson(const simulation::Campaign& campaign);

}  // namespace pkm::io::detail
