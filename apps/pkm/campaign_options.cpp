// The campaign-level settings of `pkm campaign run` and `pkm campaign sensitivity`
// (campaign_options.hpp).
#include "campaign_options.hpp"

#include "pkm/io/environment_file.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/io/uncertainty_sources.hpp"

namespace pkm::cli {

void CampaignSettingArgs::add(CLI::App& cmd, const std::string& environment_help) {
  cmd.add_option("--environment", environment, environment_help);
  cmd.add_option("--uncertainty",
                 uncertainty,
                 "instruments and environment of every step's uncertainty budgets (JSON; "
                 "default: typical datasheet values, docs/formats.md \"Uncertainty sources\")")
      ->check(CLI::ExistingFile);
  seed_option = cmd.add_option(
      "--seed", seed, "random seed of every simulated step (default: each step's own)");
}

void CampaignSettingArgs::apply(workflow::CampaignOptions& options) const {
  if (!environment.empty()) {
    options.environment = io::loadEnvironment(environment);
    options.environment_source = environment;
  }
  if (!uncertainty.empty()) {
    options.uncertainty = io::readUncertaintySources(io::readNamedText(uncertainty));
    options.uncertainty_source = uncertainty;
  }
  if (seed_option != nullptr && seed_option->count() > 0) options.seed = seed;
}

}  // namespace pkm::cli
