/// @file
/// @brief Simulation scenarios as JSON (docs/formats.md, "Scenario files"): a true machine with its
/// injected errors and the measurements taken on it. Built-in scenarios are the files of
/// data/scenarios, embedded at build time.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "pkm/simulation/campaign.hpp"
#include "pkm/simulation/cartesian_machine.hpp"

namespace pkm::io {

/// A parsed scenario.
struct Scenario {
  simulation::Campaign campaign;  ///< the machine and the measurements
  std::uint64_t seed = 1;         ///< the scenario's default seed ("seed", default 1)
  std::string machine_kind;       ///< "cartesian" or "hybrid"
  std::string machine_spec;       ///< hybrid: the machine file or built-in name
  std::string errors_spec;        ///< hybrid: the errors file or built-in name
  std::string text;               ///< the JSON text as read
  std::string source;             ///< file name, or "builtin:NAME"
};

/// Parses a scenario JSON text ("type": "simulation_scenario"). A hybrid machine's "machine" and
/// "errors" are loaded with loadExechonMachine and loadGeometricErrors; relative file names are
/// taken relative to `base_dir` when that file exists there. Throws pkm::IoError "SOURCE:LINE:
/// /json/pointer: message" for malformed JSON, unknown keys, bad values and inconsistent
/// measurements.
[[nodiscard]] Scenario parseScenarioJson(const std::string& text,
                                         const std::string& source,
                                         const std::string& base_dir = {});
/// Names of the built-in scenarios (file stems of data/scenarios/*.json), sorted.
[[nodiscard]] std::vector<std::string> builtinScenarioNames();
/// An existing file, or a built-in scenario name. Throws pkm::IoError.
[[nodiscard]] Scenario loadScenario(const std::string& spec);

/// The scenario's JSON with "seed" set to `seed` (key order kept, 2-space indent): the exact
/// inputs of a run, so that simulating it again reproduces the files.
[[nodiscard]] std::string scenarioJsonWithSeed(const Scenario& scenario, std::uint64_t seed);
/// The injected errors as JSON (docs/formats.md, "truth.json"): scenario name, seed, machine kind,
/// and the errors in the scenario's own error format (µrad for rotations).
[[nodiscard]] std::string truthJson(const Scenario& scenario, std::uint64_t seed);

}  // namespace pkm::io
