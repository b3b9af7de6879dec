/// @file
/// @brief Internal: pieces of the scenario reader shared between its source files.
#pragma once

#include <array>
#include <cmath>
#include <memory>
#include <string>

#include "io/detail/error_table_json.hpp"
#include "io/detail/json_doc.hpp"
#include "pkm/simulation/campaign.hpp"
#include "pkm/simulation/dial_gauges.hpp"
#include "pkm/simulation/environment.hpp"
#include "pkm/simulation/hybrid_tripod_errors.hpp"
#include "pkm/simulation/line_measurement.hpp"

namespace pkm::io::detail {

/// The integer at obj[key] (`fallback` when absent); fails unless it is an integer in [lo, hi].
inline int integer(const JsonDoc& doc,
                   const json& obj,
                   const std::string& ptr,
                   const char* key,
                   int fallback,
                   int lo,
                   int hi) {
  const double v = doc.number(obj, ptr, key, fallback);
  if (v != std::floor(v) || v < lo || v > hi)
    doc.fail(ptr + "/" + key, fmt::format("must be an integer in [{}, {}]", lo, hi));
  return static_cast<int>(v);
}

/// Reads one element of "measurements" at `ptr` (docs/formats.md, "Scenario files") for `machine`,
/// which gives the axis count and the nominal travel of the line. Fails through `doc`.
[[nodiscard]] simulation::LineSetup readLineSetup(const JsonDoc& doc,
                                                  const json& obj,
                                                  const std::string& ptr,
                                                  const simulation::VirtualMachine& machine);

/// The measurement's "name": required, lower-case letters, digits, '-' and '_'. Fails through
/// `doc`.
[[nodiscard]] std::string measurementName(const JsonDoc& doc,
                                          const json& obj,
                                          const std::string& ptr);

/// A "noise" value: a preset name or {"sigma", "sigma_ppm", "resolution"} divided by `scale`
/// (reading units per model unit). Fails through `doc`.
[[nodiscard]] simulation::NoiseModel readNoise(const JsonDoc& doc,
                                               const json& obj,
                                               const std::string& ptr,
                                               double scale);

/// A "hexapod" machine at `ptr` (the model loaded from `machine_path`). Fails through `doc`.
[[nodiscard]] std::shared_ptr<simulation::VirtualMachine> readHexapod(
    const JsonDoc& doc, const json& m, const std::string& ptr, const std::string& machine_path);

/// A dial-gauge measurement ("instrument": "dial_gauges"). Fails through `doc`.
[[nodiscard]] simulation::DialGaugeSetup readDialGauges(const JsonDoc& doc,
                                                        const json& obj,
                                                        const std::string& ptr);

/// A hybrid machine's "tripod_errors" object at `ptr` (lengths in mm, c0_urad and a0_urad in µrad;
/// absent keys are 0). Fails through `doc`.
[[nodiscard]] simulation::ExechonTripodErrors readTripodErrors(const JsonDoc& doc,
                                                               const json& obj,
                                                               const std::string& ptr);

/// The tripod errors as one JSON object with the keys readTripodErrors reads (truth.json).
[[nodiscard]] std::string tripodErrorsJson(const simulation::ExechonTripodErrors& errors);

/// A scenario's "environment" at `ptr`: a preset name ("ideal", "realistic") or an object
/// {"preset", "duration_h", "air", "thermal", "setup", "structure", "compliance"} whose members
/// override the preset's (docs/formats.md, "Scenario files"; an object is named "custom"). Fails
/// through `doc`.
[[nodiscard]] simulation::Environment readEnvironment(const JsonDoc& doc,
                                                      const json& obj,
                                                      const std::string& ptr);

/// An environment's "compliance" object at `ptr` (docs/formats.md, "Scenario files"): overrides
/// the members of `c` it names and switches the source on unless "enabled" is false. Fails
/// through `doc`.
void readCompliance(const JsonDoc& doc,
                    const json& obj,
                    const std::string& ptr,
                    simulation::ComplianceEnvironment& c);
/// An environment's "geometry" object (GeometryEnvironment, docs/formats.md): its members override
/// `g`'s; giving the object switches the source on unless "enabled": false. Fails through `doc`.
void readGeometry(const JsonDoc& doc,
                  const json& obj,
                  const std::string& ptr,
                  simulation::GeometryEnvironment& g);

/// ",\n  \"unmodelled_geometry\": {...}" with the geometry drawn into the campaign's machine
/// (a hexapod's strut lead errors and joint offsets, a hybrid tripod's leg lead errors), or ""
/// when it has none.
[[nodiscard]] std::string geometryTruthJson(const simulation::Campaign& campaign);

/// The built-in scenario texts (generated from data/scenarios/*.json): {file stem, JSON text}.
const std::vector<std::pair<std::string_view, std::string_view>>& embeddedScenarios();

}  // namespace pkm::io::detail
