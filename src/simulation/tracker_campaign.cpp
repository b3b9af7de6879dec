// The laser-tracker part of a campaign (campaign.hpp): validateTrackers and runLaserTrackers.
#include <set>

#include "pkm/core/error.hpp"
#include "pkm/simulation/campaign.hpp"

namespace pkm::simulation {

void validateTrackers(const Campaign& campaign) {
  if (campaign.trackers.empty()) return;
  PKM_CHECK(campaign.machine != nullptr, "campaign '{}' has no machine", campaign.name);
  std::set<std::string> names;
  for (const LineSetup& m : campaign.measurements) names.insert(m.name);
  for (const DialGaugeSetup& d : campaign.constrained) names.insert(d.name);
  for (const TouchProbeSetup& p : campaign.probes) names.insert(p.name);
  for (const TrackerSetup& t : campaign.trackers) {
    t.validate();
    PKM_CHECK(dynamic_cast<const HexapodVirtualMachine*>(campaign.machine.get()) != nullptr,
              "{}: a laser tracker measurement needs a hexapod",
              t.name);
    PKM_CHECK(names.insert(t.name).second, "two measurements are named '{}'", t.name);
  }
}

std::vector<TrackerResult> runLaserTrackers(const Campaign& campaign, std::uint64_t seed) {
  campaign.validate();
  validateTrackers(campaign);
  std::vector<TrackerResult> results;
  for (const TrackerSetup& setup : campaign.trackers) {
    RandomStream rng(seed, setup.name);
    auto& hexapod = dynamic_cast<HexapodVirtualMachine&>(*campaign.machine);
    results.push_back({&setup, simulateLaserTracker(hexapod, setup, rng)});
  }
  return results;
}

}  // namespace pkm::simulation
