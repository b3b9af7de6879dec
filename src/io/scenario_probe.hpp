/// @file
/// @brief Internal: the touch-probe measurements of a scenario ("instrument": "touch_probe",
/// docs/formats.md, "Scenario files") and their part of truth.json.
#pragma once

#include <string>

#include "io/detail/json_doc.hpp"
#include "pkm/simulation/campaign.hpp"

namespace pkm::io::detail {

/// A touch-probe measurement at `ptr` on the Exechon of the hybrid machine file or built-in
/// `machine_path`; `machine_kind` must be "hybrid". Fails through `doc` (also when the name is
/// that of a measurement already in `campaign`).
[[nodiscard]] simulation::TouchProbeSetup readTouchProbe(const JsonDoc& doc,
                                                         const json& obj,
                                                         const std::string& ptr,
                                                         const std::string& machine_kind,
                                                         const std::string& machine_path,
                                                         const simulation::Campaign& campaign);

/// The truth.json member "touch_probes" (",\n  \"touch_probes\": [...]"; empty when there are
/// none), to go before the closing brace.
[[nodiscard]] std::string touchProbeTruthJson(const simulation::Campaign& campaign);

}  // namespace pkm::io::detail
