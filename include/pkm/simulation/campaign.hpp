/// @file
/// @brief A simulated measurement campaign: a true machine and the line measurements taken on it,
/// run with one scenario seed (docs/formats.md, "Scenario files"). Reading the scenario JSON is in
/// pkm/io/scenario.hpp; writing the files in pkm/io/measurement_files.hpp.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "pkm/simulation/dial_gauges.hpp"
#include "pkm/simulation/environment.hpp"
#include "pkm/simulation/exechon_tracker.hpp"
#include "pkm/simulation/hybrid_tracker.hpp"
#include "pkm/simulation/laser_tracker.hpp"
#include "pkm/simulation/line_measurement.hpp"
#include "pkm/simulation/touch_probe.hpp"
#include "pkm/simulation/virtual_machine.hpp"

namespace pkm::simulation {

/// What to simulate.
struct Campaign {
  std::string name;                         ///< scenario name
  std::string description;                  ///< free text
  std::shared_ptr<VirtualMachine> machine;  ///< the true machine (required)
  std::vector<LineSetup> measurements;      ///< in the order they are taken; names unique
  /// Constrained-motion measurements with dial gauges (Lee et al., "Development of a Parallel-Typed
  /// CNC Machine"); need a HexapodVirtualMachine.
  std::vector<DialGaugeSetup> constrained;
  /// Laser-tracker measurements (point or 6-DOF pose); need a HexapodVirtualMachine. Checked by
  /// validateTrackers (names unique among all measurements).
  std::vector<TrackerSetup> trackers;
  /// Laser-tracker measurements of the Exechon PKM of a hybrid machine with tripod errors
  /// (exechon_tracker.hpp); checked by validateTrackers, run by runExechonTrackers.
  std::vector<ExechonTrackerSetup> exechon_trackers;
  /// Laser-tracker measurements of the tool of a hybrid machine over all five axes
  /// (hybrid_tracker.hpp); checked by validateTrackers, run by runHybridTrackers.
  std::vector<HybridTrackerSetup> hybrid_trackers;
  /// Touch-probe measurements on a master ring (Lee et al. 2019); need a hybrid (Exechon) machine.
  /// Run with runTouchProbes (pkm/simulation/touch_probe.hpp).
  std::vector<TouchProbeSetup> probes;
  /// The workshop's environment (environment.hpp); the default is ideal (every source off).
  Environment environment;
  /// Throws pkm::InvalidArgument when there is no machine, a set-up is invalid, a line's size is
  /// not the machine's axis count, two measurements (of either kind) share a name, or dial gauges
  /// are set up on a machine that is not a hexapod.
  void validate() const;
};

/// The campaign time each measurement of an active environment occupies, s: T/N with T =
/// environment.duration_h and N the number of line and hexapod laser-tracker measurements (lines
/// first, in order, then trackers). Line k starts at elapsed + k·window, tracker j at elapsed +
/// (lines + j)·window (elapsed = environment.elapsed_h). A
/// hexapod's struts keep, during one measurement, the thermal growth of the window's middle
/// (Environment::strutGrowth).
[[nodiscard]] double measurementWindowS(const Campaign& campaign);

/// Gives every touch probe of the campaign the environment's pre-travel lobing
/// (SetupEnvironment::probe_lobing_mm and probe_lobes) when the set-up source is on (leaves them
/// as they are otherwise), and its master ring (steel) the expansion of the material temperature
/// at the pass's start when the thermal source is on (zero otherwise). Call after setting
/// campaign.environment.
void applyProbeEnvironment(Campaign& campaign);

/// Gives the campaign's machine the environment's compliance (ComplianceEnvironment,
/// compliance.hpp) when that source is on, and takes it away when it is off: a hexapod's strut
/// compliance (HexapodVirtualMachine::setCompliance), a Cartesian machine's axis sag
/// (CartesianMachine::setSag), a hybrid machine's X2/Y2 sag and its tripod's leg compliance
/// (HybridVirtualMachine::setSag, setTripodCompliance). Call after setting campaign.environment.
void applyMachineEnvironment(Campaign& campaign);
/// Puts the environment's unmodelled geometry (GeometryEnvironment) into the campaign's true
/// machine, drawn from RandomStream(seed, "environment/geometry"): a hexapod's strut lead errors
/// and U-joint offsets (drawHexapodGeometry, HexapodVirtualMachine::setUnmodelledGeometry), a
/// hybrid machine's tripod leg lead errors (drawLegLeadErrors). Replaces what an earlier call put
/// there, so with the geometry off the machine is as built. The machine keeps it for every pass of
/// the measurements (it is the machine's, not the measurement's). Call after setting
/// campaign.environment and the seed. Throws pkm::InvalidArgument for an invalid geometry.
void applyGeometryEnvironment(Campaign& campaign, std::uint64_t seed);

/// One measurement's result.
struct MeasurementResult {
  const LineSetup* setup = nullptr;  ///< points into the campaign
  std::vector<LineRun> runs;         ///< one per run
};

/// Runs every measurement. Measurement k draws only from RandomStream(seed, setup.name), so the
/// numbers of one measurement do not depend on which others exist. Identical results for the same
/// seed on every platform. In an active environment, line measurement k of N occupies the campaign
/// time [k·T/N, (k+1)·T/N) (T = environment.duration_h) and its environment draws from
/// RandomStream(seed, setup.name + "/environment"). The lasers' ppm scale error is one standard
/// normal draw of RandomStream(seed, "instrument-scale") for the whole session (simulateLine with
/// a scale_z): a laser's environmental compensation holds over a test. Throws
/// pkm::InvalidArgument
/// (Campaign::validate, simulateLine).
[[nodiscard]] std::vector<MeasurementResult> runCampaign(const Campaign& campaign,
                                                         std::uint64_t seed);

/// One constrained-motion measurement's result.
struct ConstrainedResult {
  const DialGaugeSetup* setup = nullptr;   ///< points into the campaign
  std::vector<DialGaugeStation> stations;  ///< the reference (station 0), then the stations
};

/// Runs every constrained-motion measurement, each from RandomStream(seed, setup.name). Throws
/// pkm::InvalidArgument (Campaign::validate, simulateDialGauges).
[[nodiscard]] std::vector<ConstrainedResult> runConstrainedMotion(const Campaign& campaign,
                                                                  std::uint64_t seed);

/// Throws pkm::InvalidArgument when a tracker set-up is invalid, the machine is not a hexapod,
/// or a tracker's name is that of another measurement of any kind.
void validateTrackers(const Campaign& campaign);

/// One laser-tracker measurement's result.
struct TrackerResult {
  const TrackerSetup* setup = nullptr;   ///< points into the campaign
  std::vector<TrackerReading> readings;  ///< one per commanded pose
};

/// Runs every laser-tracker measurement, each from RandomStream(seed, setup.name). Throws
/// pkm::InvalidArgument (Campaign::validate, validateTrackers, simulateLaserTracker).
[[nodiscard]] std::vector<TrackerResult> runLaserTrackers(const Campaign& campaign,
                                                          std::uint64_t seed);

/// One Exechon tracker measurement's result.
struct ExechonTrackerResult {
  const ExechonTrackerSetup* setup = nullptr;   ///< points into the campaign
  std::vector<ExechonTrackerReading> readings;  ///< one per commanded pose
};

/// Runs every Exechon tracker measurement, each from RandomStream(seed, setup.name), on the
/// hybrid machine's tripod (nominal and true models). Throws pkm::InvalidArgument
/// (validateTrackers, simulateExechonTracker).
[[nodiscard]] std::vector<ExechonTrackerResult> runExechonTrackers(const Campaign& campaign,
                                                                   std::uint64_t seed);

/// One hybrid tracker measurement's result.
struct HybridTrackerResult {
  const HybridTrackerSetup* setup = nullptr;   ///< points into the campaign
  std::vector<HybridTrackerReading> readings;  ///< one per command
};

/// Runs every hybrid tracker measurement, each from RandomStream(seed, setup.name). Throws
/// pkm::InvalidArgument (validateTrackers, simulateHybridTracker).
[[nodiscard]] std::vector<HybridTrackerResult> runHybridTrackers(const Campaign& campaign,
                                                                 std::uint64_t seed);

}  // namespace pkm::simulation
