/// @file
/// @brief `pkm simulate`: a measurement campaign on a virtual machine with known errors
/// (docs/formats.md, "Measurement files", "Scenario files"): every measurement of a scenario
/// simulated with one seed, as the files an instrument would export, with truth.json and the
/// scenario itself.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "pkm/io/named_text.hpp"
#include "pkm/io/scenario.hpp"

namespace pkm::workflow {

/// A simulation run.
struct SimulateOptions {
  std::string scenario;               ///< a scenario file or a built-in scenario's name (required)
  std::filesystem::path out;          ///< the folder to write into (required)
  std::optional<std::uint64_t> seed;  ///< the random seed; default the scenario's "seed"
  bool force = false;                 ///< replace files that exist
  /// Throws pkm::IoError "give a SCENARIO ..." or "give --out DIR" for a missing field.
  void validate() const;
};

/// One file of a simulation: its name in the output folder and its text.
struct SimulatedFile {
  std::string name;
  std::string text;
};

/// What a simulation produced.
struct SimulateResult {
  std::string scenario;  ///< the scenario's name
  std::uint64_t seed = 0;
  std::vector<SimulatedFile> files;  ///< in the order written
};

/// A built-in scenario: its name, number of measurements and description (`simulate --list`).
struct ScenarioInfo {
  std::string name;
  std::size_t measurements = 0;
  std::string description;
};

/// Every built-in scenario, sorted by name.
[[nodiscard]] std::vector<ScenarioInfo> listScenarios();

/// Simulates every measurement of the scenario and returns the files without writing them.
/// Throws pkm::IoError for a scenario that cannot be loaded (naming it and the line).
[[nodiscard]] SimulateResult simulateScenario(const std::string& scenario,
                                              std::optional<std::uint64_t> seed);

/// Simulates every measurement of a loaded (and possibly modified) scenario with `seed`; as
/// simulateScenario. The scenario's machine is shared: its unmodelled geometry is set from
/// `seed` (simulation::applyGeometryEnvironment).
[[nodiscard]] SimulateResult simulateLoadedScenario(const io::Scenario& scenario,
                                                    std::uint64_t seed);

/// Simulates the scenario given as JSON text (a front end's document, e.g. a Python dict; the
/// format of a scenario file, docs/formats.md "Scenario files"), named `scenario.name` in
/// messages; relative file names in it (a hybrid machine's "machine" and "errors") are taken
/// relative to `base_dir` where that file exists. Throws pkm::IoError "NAME:LINE: /pointer:
/// message" for a bad scenario.
[[nodiscard]] SimulateResult simulateScenarioText(const io::NamedText& scenario,
                                                  std::optional<std::uint64_t> seed,
                                                  const std::string& base_dir = {});

/// Writes the files of `result` into `dir` (created), replacing existing files only with
/// `force`. Throws pkm::IoError "DIR: cannot create the directory" and (without `force`, before
/// anything is written) "PATH: exists; refusing to overwrite (use --force)".
void writeSimulation(const SimulateResult& result, const std::filesystem::path& dir, bool force);

/// Simulates, then writes the files into `options.out` (created). Nothing is written for a
/// failing scenario, and (without `force`) nothing when any of the files exists: pkm::IoError
/// "PATH: exists; refusing to overwrite (use --force)".
[[nodiscard]] SimulateResult runSimulate(const SimulateOptions& options);

}  // namespace pkm::workflow
