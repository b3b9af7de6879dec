/// @file
/// @brief A simulation environment (simulation::Environment, docs/simulation-errors.md) as a file
/// of its own, the argument of `pkm campaign run --environment` and of `pkm campaign sensitivity
/// --environment` (docs/campaign.md), and its numeric parameters by dotted path (the sensitivity
/// study's `--source`). The keys are those of a scenario's "environment" (docs/formats.md,
/// "Scenario files"): a preset name, or an object {"preset", "duration_h", "air", "thermal",
/// "setup", "structure"} whose members override the preset's.
#pragma once

#include <string>
#include <vector>

#include "pkm/io/named_text.hpp"
#include "pkm/simulation/environment.hpp"

namespace pkm::io {

/// Parses an environment document: a JSON object with the keys of a scenario's "environment", or
/// a JSON string naming a preset. Throws pkm::IoError "NAME:LINE: /pointer: message" for invalid
/// JSON, an unknown key or preset, a value of the wrong type or out of range (the message names
/// the key).
[[nodiscard]] simulation::Environment parseEnvironmentJson(const NamedText& text);

/// `spec` is an existing file (parseEnvironmentJson of its text) or a preset name
/// (simulation::environmentPreset). Throws pkm::IoError "SPEC: no such file, and not an
/// environment preset (ideal, realistic)" otherwise, and as parseEnvironmentJson.
[[nodiscard]] simulation::Environment loadEnvironment(const std::string& spec);

/// One numeric parameter of an environment, named by the dotted path of its key in the JSON
/// ("air.temperature_sensor.offset", "setup.beam_misalignment_urad", "thermal.warmup_drift_mm.2"),
/// in the JSON's unit.
struct EnvironmentParameter {
  std::string path;  ///< dotted key path
  std::string unit;  ///< unit of the JSON value ("K", "Pa", "%", "mm", "µm", "µrad", "1/K", ...)
  std::string meaning;  ///< one line
};

/// Every numeric parameter, in the order of docs/formats.md's table (materials given by name and
/// the "enabled" flags are not numeric parameters).
[[nodiscard]] const std::vector<EnvironmentParameter>& environmentParameters();

/// The value of parameter `path` in `environment`, in the JSON's unit. Throws pkm::InvalidArgument
/// "unknown environment parameter 'PATH' (valid: ...)" listing every valid path.
[[nodiscard]] double environmentParameter(const simulation::Environment& environment,
                                          const std::string& path);

/// Sets parameter `path` to `value` (JSON unit) and switches its group ("air", "thermal", "setup",
/// "structure") on, every other value kept: the same environment as a JSON object that gives only
/// this key on top of `environment`. The name becomes "custom". Throws pkm::InvalidArgument for an
/// unknown path (as environmentParameter), a non-finite value, a non-integer probe_lobes, or a
/// value the environment refuses (simulation::Environment::isValid, the reason in the message).
void setEnvironmentParameter(simulation::Environment& environment,
                             const std::string& path,
                             double value);

}  // namespace pkm::io
