/// @file
/// @brief What `pkm campaign run` and `pkm campaign sensitivity` share: the campaign-level
/// settings --environment, --uncertainty and --seed (docs/campaign.md), and the sensitivity
/// subcommand's registration.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

#include "pkm/workflow/campaign.hpp"

namespace pkm::cli {

/// --environment PRESET|FILE, --uncertainty FILE and --seed N of a campaign command.
struct CampaignSettingArgs {
  std::string environment;  ///< a preset name or an environment file ("": each step's own)
  std::string uncertainty;  ///< an uncertainty-sources file ("": the typical values)
  std::uint64_t seed = 0;
  CLI::Option* seed_option = nullptr;  ///< set by add(); counts whether --seed was given
  /// Adds the three options to `cmd`; `environment_help` describes --environment.
  void add(CLI::App& cmd, const std::string& environment_help);
  /// Loads the environment (io::loadEnvironment) and the uncertainty sources
  /// (io::readUncertaintySources) into `options`, with the seed when given. Throws pkm::IoError
  /// "FILE:LINE: /pointer: message" for a bad file and "SPEC: no such file, and not an
  /// environment preset" for a name that is neither.
  void apply(workflow::CampaignOptions& options) const;
};

/// Adds `pkm campaign sensitivity` to the `campaign` group (campaign_sensitivity_command.cpp).
void addCampaignSensitivityCommand(CLI::App& campaign);

}  // namespace pkm::cli
