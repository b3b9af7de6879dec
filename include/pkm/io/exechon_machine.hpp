/// @file
/// @brief ExechonMachine: an Exechon tripod with its C/A wrist, optionally carried by the extending
/// axes X2/Y2 of a hybrid machine, as read from a JSON machine file (docs/machine-format.md).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "pkm/io/joint_rates.hpp"
#include "pkm/kinematics/exechon_model.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hybrid_model.hpp"

namespace pkm::io {

/// Everything a machine file says about an Exechon machine.
struct ExechonMachine {
  kinematics::ExechonModel model;
  kinematics::FkOptions fk;                  ///< tripod forward-kinematics settings
  std::optional<JointRateSpec> joint_rates;  ///< leg and wrist rate limits, when given
  /// The extending axes X2 (carries the PKM) and Y2 (carries the work table) when the machine is a
  /// hybrid one (MXT700S parallelism paper); absent for a stand-alone tripod.
  std::optional<kinematics::HybridMachineModel> hybrid;
  std::string description;
  std::string source;                ///< file path, or "builtin:NAME"
  std::vector<std::string> notices;  ///< things the reader assumed, for the user to see
};

/// Parses an Exechon machine JSON text ("type": "exechon"). Throws pkm::IoError "SOURCE:LINE:
/// /json/pointer: message" for malformed JSON, unknown keys, wrong types, non-finite numbers, bad
/// signs or ranges, and unusable geometry (ExechonModel::validate, HybridMachineModel::validate).
[[nodiscard]] ExechonMachine parseExechonJson(const std::string& text, const std::string& source);

/// Reads and parses an Exechon machine file. Throws pkm::IoError.
[[nodiscard]] ExechonMachine readExechonJson(const std::string& path);

/// Writes the machine in the format parseExechonJson reads (lengths round-trip exactly; angles,
/// written in degrees, to within one unit in the last place).
[[nodiscard]] std::string writeExechonJson(const ExechonMachine& machine);

}  // namespace pkm::io
