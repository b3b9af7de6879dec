/// @file
/// @brief The stations of an automated calibration by constrained motion (docs/linuxcnc.md,
/// "Automated calibration by constrained motion"; Lee et al., "Development of a Parallel-Typed CNC
/// Machine", §3): planar moves (Δx, Δy, Δc) from a reference, chosen by pkm's pose planner
/// (calibration::planFromJacobians) among the moves the machine can make, so that the
/// plane-contact equations identify as much of the 42-parameter geometry as they can.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

#include "pkm/calibration/identifiability.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "pkm/simulation/dial_gauges.hpp"

namespace pkm::live {

/// How stations are planned.
struct GaugeStationOptions {
  /// Stations to fit with: Lee et al. take three times as many equations as unknowns (36).
  int count = 36;
  int holdout = 4;            ///< further stations kept out of the fit (the held-out check)
  double reach = 200.0;       ///< candidates' |Δx|, |Δy| up to this, machine unit (> 0)
  double c_range_deg = 20.0;  ///< candidates' |Δc| up to this, degrees (≥ 0)
  int grid = 9;               ///< candidates per axis of x and y (odd, ≥ 3); c takes 5 values
  /// The world axis limits LinuxCNC enforces, x y z a b c (degrees for a b c); every candidate
  /// and its approach point must lie within them.
  std::array<double, 6> axis_min{}, axis_max{};
  calibration::ObservabilityIndex index = calibration::ObservabilityIndex::kO1;
  /// Throws pkm::InvalidArgument naming the field for count < 1, holdout < 0, reach ≤ 0, a
  /// negative c range, or an even or small grid.
  void validate() const;
};

/// The plan.
struct GaugeStationPlan {
  std::vector<Eigen::Vector3d> fit;      ///< (Δx, Δy, Δc): machine unit, rad
  std::vector<Eigen::Vector3d> holdout;  ///< the same, kept out of the fit
  int candidates = 0;                    ///< moves the machine can make, of those tried
  int tried = 0;                         ///< candidates tried
  int identifiable = 0;      ///< rank of the candidates' plane-contact Jacobian (of 42 parameters)
  double index_value = 0.0;  ///< the planner's index of the chosen stations
  double random_baseline = 0.0;  ///< the index of random choices of as many (the planner's)
};

/// Plans the stations of `setup` (its reference, gauge points, normal and approach are used;
/// its stations are ignored) on `machine`: a grid of (Δx, Δy, Δc) whose command and approach
/// point pass every check of `pkm hexapod check` (workflow::checkHexapodPose) and the axis limits,
/// and whose approach moves every strut the way the reference's approach does (all lengthen or
/// all shorten: each strut always arrives from the same side, Lee et al. Fig. 6); their
/// plane-contact Jacobians (calibration::gaugeHeights at the nominal readings, less the
/// reference's) projected on the identifiable directions; options.count chosen by the planner, then
/// options.holdout spread over the rest. Throws pkm::InvalidArgument when the reference fails those
/// checks, its approach moves struts both ways, or fewer candidates than count + holdout pass them.
[[nodiscard]] GaugeStationPlan planGaugeStations(const io::HexapodMachine& machine,
                                                 const simulation::DialGaugeSetup& setup,
                                                 const GaugeStationOptions& options);

}  // namespace pkm::live
