#include "pkm/simulation/campaign.hpp"

#include <algorithm>
#include <set>

#include "pkm/core/error.hpp"
#include "pkm/simulation/cartesian_machine.hpp"
#include "pkm/simulation/hexapod_virtual_machine.hpp"
#include "pkm/simulation/hybrid_virtual_machine.hpp"
#include "pkm/simulation/unmodelled_geometry.hpp"

namespace pkm::simulation {

namespace {
constexpr double kSecondsPerHour = 3600.0;
}  // namespace

void Campaign::validate() const {
  PKM_CHECK(machine != nullptr, "campaign '{}' has no machine", name);
  std::string why;
  PKM_CHECK(environment.isValid(&why), "campaign '{}': environment: {}", name, why);
  const auto axes = static_cast<Eigen::Index>(machine->axisNames().size());
  std::set<std::string> names;
  for (const LineSetup& m : measurements) {
    m.validate();
    PKM_CHECK(m.line.start.size() == axes,
              "{}: the line has {} axes, the machine {}",
              m.name,
              m.line.start.size(),
              axes);
    PKM_CHECK(names.insert(m.name).second, "two measurements are named '{}'", m.name);
  }
  for (const DialGaugeSetup& d : constrained) {
    d.validate();
    PKM_CHECK(dynamic_cast<const HexapodVirtualMachine*>(machine.get()) != nullptr,
              "{}: dial gauges need a hexapod",
              d.name);
    PKM_CHECK(names.insert(d.name).second, "two measurements are named '{}'", d.name);
  }
}

double measurementWindowS(const Campaign& campaign) {
  const std::size_t n = campaign.measurements.size() + campaign.trackers.size();
  return campaign.environment.duration_h * kSecondsPerHour /
         static_cast<double>(std::max<std::size_t>(1, n));
}

std::vector<MeasurementResult> runCampaign(const Campaign& campaign, std::uint64_t seed) {
  campaign.validate();
  std::vector<MeasurementResult> results;
  const Environment& env = campaign.environment;
  const double window_s = measurementWindowS(campaign);
  auto* hexapod = dynamic_cast<HexapodVirtualMachine*>(campaign.machine.get());
  auto* hybrid = dynamic_cast<HybridVirtualMachine*>(campaign.machine.get());
  // The laser's ppm accuracy (its environmental compensation) holds over the session: one scale
  // error, in standard deviations, for every line (NoiseModel::scaleFor).
  const double scale_z = RandomStream(seed, "instrument-scale").normal();
  for (const LineSetup& setup : campaign.measurements) {
    RandomStream rng(seed, setup.name);
    if (!env.active()) {
      results.push_back({&setup, simulateLine(*campaign.machine, setup, rng, nullptr, scale_z)});
      continue;
    }
    const double start_s =
        env.elapsed_h * kSecondsPerHour + static_cast<double>(results.size()) * window_s;
    if (hexapod != nullptr) hexapod->setStrutGrowth(env.strutGrowth(start_s + window_s / 2));
    if (hybrid != nullptr) hybrid->setPkmTilt(env.pkmTilt(start_s + window_s / 2));
    MeasurementConditions conditions(
        env, start_s, window_s, readingCount(setup), streamSeed(seed, setup.name + "/environment"));
    results.push_back({&setup, simulateLine(*campaign.machine, setup, rng, &conditions, scale_z)});
  }
  if (hexapod != nullptr) hexapod->setStrutGrowth(0.0);
  if (hybrid != nullptr) hybrid->setPkmTilt(Eigen::Vector3d::Zero());
  return results;
}

void applyProbeEnvironment(Campaign& campaign) {
  const Environment& env = campaign.environment;
  // The master ring (steel) at the material temperature of the pass's start.
  const double ring_expansion =
      env.thermal.enabled
          ? *expansionCoefficient("steel") *
                (env.thermal.material_temperature_c.smooth(env.elapsed_h / env.duration_h) - 20.0)
          : 0.0;
  for (TouchProbeSetup& p : campaign.probes) {
    p.ring_expansion = ring_expansion;
    if (!env.setup.enabled) continue;
    p.lobing = env.setup.probe_lobing_mm;
    p.lobes = env.setup.probe_lobes;
  }
}

void applyMachineEnvironment(Campaign& campaign) {
  const ComplianceEnvironment& c = campaign.environment.compliance;
  const bool on = c.enabled;
  if (auto* h = dynamic_cast<HexapodVirtualMachine*>(campaign.machine.get()))
    h->setCompliance(on ? std::optional<HexapodCompliance>(c.hexapod) : std::nullopt);
  if (auto* m = dynamic_cast<CartesianMachine*>(campaign.machine.get()))
    m->setSag(on ? c.cartesian : std::array<AxisSag, 3>{});
  if (auto* y = dynamic_cast<HybridVirtualMachine*>(campaign.machine.get())) {
    y->setSag(on ? c.x2 : AxisSag{}, on ? c.y2 : AxisSag{});
    y->setTripodCompliance(on ? std::optional<ExechonCompliance>(c.exechon) : std::nullopt);
  }
}

void applyGeometryEnvironment(Campaign& campaign, std::uint64_t seed) {
  const GeometryEnvironment& env = campaign.environment.geometry;
  RandomStream rng(seed, "environment/geometry");
  if (auto* hexapod = dynamic_cast<HexapodVirtualMachine*>(campaign.machine.get()))
    hexapod->setUnmodelledGeometry(drawHexapodGeometry(env, hexapod->nominal(), rng));
  if (auto* hybrid = dynamic_cast<HybridVirtualMachine*>(campaign.machine.get());
      hybrid != nullptr && hybrid->tripod())
    hybrid->setTripodLegLeadErrors(drawLegLeadErrors(env, hybrid->tripod()->nominal(), rng));
}

std::vector<ConstrainedResult> runConstrainedMotion(const Campaign& campaign, std::uint64_t seed) {
  campaign.validate();
  std::vector<ConstrainedResult> results;
  for (const DialGaugeSetup& setup : campaign.constrained) {
    RandomStream rng(seed, setup.name);
    auto& hexapod = dynamic_cast<HexapodVirtualMachine&>(*campaign.machine);
    results.push_back({&setup, simulateDialGauges(hexapod, setup, rng)});
  }
  return results;
}

}  // namespace pkm::simulation
