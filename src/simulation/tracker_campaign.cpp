// The laser-tracker part of a campaign (campaign.hpp): validateTrackers and runLaserTrackers.
#include <set>

#include "pkm/core/error.hpp"
#include "pkm/simulation/campaign.hpp"
#include "pkm/simulation/hybrid_virtual_machine.hpp"

namespace pkm::simulation {

void validateTrackers(const Campaign& campaign) {
  if (campaign.trackers.empty() && campaign.exechon_trackers.empty() &&
      campaign.hybrid_trackers.empty())
    return;
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
  for (const HybridTrackerSetup& t : campaign.hybrid_trackers) {
    t.validate();
    PKM_CHECK(dynamic_cast<const HybridVirtualMachine*>(campaign.machine.get()) != nullptr,
              "{}: a hybrid laser tracker measurement needs a hybrid machine",
              t.name);
    PKM_CHECK(names.insert(t.name).second, "two measurements are named '{}'", t.name);
  }
  for (const ExechonTrackerSetup& t : campaign.exechon_trackers) {
    t.validate();
    const auto* hybrid = dynamic_cast<const HybridVirtualMachine*>(campaign.machine.get());
    PKM_CHECK(hybrid != nullptr && hybrid->tripod().has_value(),
              "{}: an Exechon laser tracker measurement needs a hybrid machine with "
              "\"tripod_errors\"",
              t.name);
    PKM_CHECK(names.insert(t.name).second, "two measurements are named '{}'", t.name);
  }
}

std::vector<HybridTrackerResult> runHybridTrackers(const Campaign& campaign, std::uint64_t seed) {
  campaign.validate();
  validateTrackers(campaign);
  std::vector<HybridTrackerResult> results;
  for (const HybridTrackerSetup& setup : campaign.hybrid_trackers) {
    RandomStream rng(seed, setup.name);
    auto& hybrid = dynamic_cast<HybridVirtualMachine&>(*campaign.machine);
    results.push_back({&setup, simulateHybridTracker(hybrid, setup, rng)});
  }
  return results;
}

std::vector<ExechonTrackerResult> runExechonTrackers(const Campaign& campaign, std::uint64_t seed) {
  campaign.validate();
  validateTrackers(campaign);
  std::vector<ExechonTrackerResult> results;
  for (const ExechonTrackerSetup& setup : campaign.exechon_trackers) {
    RandomStream rng(seed, setup.name);
    const HybridTripod& tripod =
        *dynamic_cast<const HybridVirtualMachine&>(*campaign.machine).tripod();
    results.push_back({&setup,
                       simulateExechonTracker(tripod.nominal(),
                                              tripod.actual(),
                                              tripod.fkOptions(),
                                              setup,
                                              rng,
                                              tripod.compliance() ? &*tripod.compliance() : nullptr,
                                              tripod.legLeadErrors())});
  }
  return results;
}

std::vector<TrackerResult> runLaserTrackers(const Campaign& campaign, std::uint64_t seed) {
  campaign.validate();
  validateTrackers(campaign);
  std::vector<TrackerResult> results;
  const double window_s = measurementWindowS(campaign);
  for (const TrackerSetup& setup : campaign.trackers) {
    RandomStream rng(seed, setup.name);
    auto& hexapod = dynamic_cast<HexapodVirtualMachine&>(*campaign.machine);
    // The window's middle: trackers follow the line measurements on the campaign clock.
    const double k = static_cast<double>(campaign.measurements.size() + results.size()) + 0.5;
    const double elapsed_s = campaign.environment.elapsed_h * 3600.0;
    hexapod.setStrutGrowth(campaign.environment.strutGrowth(elapsed_s + k * window_s));
    results.push_back({&setup, simulateLaserTracker(hexapod, setup, rng)});
    hexapod.setStrutGrowth(0.0);
  }
  return results;
}

}  // namespace pkm::simulation
