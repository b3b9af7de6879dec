/// @file
/// @brief Lee et al.'s ("Development of a Parallel-Typed CNC Machine") calibration by constrained
/// motion: three dial gauges on the hexapod platform touch the table; at each station the platform
/// is moved parallel to the table and then driven until the gauges read zero again, and the
/// commanded strut lengths are recorded.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "pkm/simulation/hexapod_virtual_machine.hpp"
#include "pkm/simulation/noise.hpp"

namespace pkm::simulation {

/// The set-up of a constrained-motion measurement.
struct DialGaugeSetup {
  std::string name = "dial-gauges";  ///< names the random stream in a campaign
  /// The gauge tips in the tool frame (the commanded pose's frame), mm; not collinear.
  std::array<Eigen::Vector3d, 3> gauge_points{
      Eigen::Vector3d(100, 0, 0), Eigen::Vector3d(-50, 86.6, 0), Eigen::Vector3d(-50, -86.6, 0)};
  /// The unit normal of the table plane the tips touch, world frame.
  Eigen::Vector3d table_normal = Eigen::Vector3d::UnitZ();
  /// The command (x, y, z, a, b, c; mm, rad) at which the gauges are zeroed.
  Eigen::VectorXd reference;
  /// The stations: planar moves (Δx, Δy, Δc) from the reference, mm and rad, in the table plane
  /// for table_normal = ẑ.
  std::vector<Eigen::Vector3d> stations;
  /// Noise of a gauge reading, mm (a dial gauge: resolution 1 µm).
  NoiseModel noise;
  /// The operator stops when every |reading| ≤ tolerance, mm.
  double tolerance = 1e-3;
  /// The operator gives up after this many readings at one station.
  int max_iterations = 20;
  /// Every move to a reading's command first goes to that command lowered by this much along z,
  /// mm, so that each strut reaches it from the same side and backlash is always taken up the
  /// same way (Lee et al., Fig. 6); 0: straight to the command.
  double approach = 0.0;
  /// Throws pkm::InvalidArgument for a reference that is not six finite values, collinear gauges,
  /// a zero normal, a tolerance ≤ 0, max_iterations < 1, or a negative approach.
  void validate() const;
};

/// The record of one station.
struct DialGaugeStation {
  int station = 0;          ///< from 1; 0 is the reference
  Eigen::VectorXd command;  ///< final command (mm, rad)
  kinematics::StrutVector lengths =
      kinematics::StrutVector::Zero();  ///< commanded strut readings, mm
  std::array<double, 3> readings{};     ///< final gauge readings, mm
  int iterations = 0;                   ///< readings taken
  bool converged = false;               ///< all |readings| ≤ tolerance
};

/// The machine side of a constrained-motion measurement: the platform's moves and the three
/// gauges. A simulated machine (simulateDialGauges) or a running controller (pkm::live).
class ConstrainedMotionRig {
 public:
  virtual ~ConstrainedMotionRig() = default;
  /// Moves the platform to `command` (x, y, z, a, b, c; mm, rad, the nominal model's pose) and
  /// returns the strut readings the controller commanded, mm.
  virtual kinematics::StrutVector moveTo(const Eigen::VectorXd& command) = 0;
  /// Zeroes the three gauges where the platform stands.
  virtual void zeroGauges() = 0;
  /// The three gauges' readings since zeroGauges, mm, positive when a tip moves along the table
  /// normal.
  virtual Eigen::Vector3d readGauges() = 0;
};

/// The operator of the measurement (Lee et al., §3) on any rig: moves to the reference, zeroes
/// the gauges, then at each station starts at the reference plus the planar move and, while a
/// reading exceeds the tolerance, corrects (z, a, b) of the command by the readings through the
/// nominal sensitivity of the tip heights to (z, a, b) (a 3×3 solve by central differences of
/// n·(R t + p) over the commanded pose), as an operator jogs the platform; every move approaches
/// as setup.approach says. `on_station` (when set) is called with each station's record as it
/// ends. Returns the reference (station 0) and the stations. Throws pkm::InvalidArgument for an
/// invalid set-up; what the rig throws passes through.
[[nodiscard]] std::vector<DialGaugeStation> runConstrainedMotion(
    ConstrainedMotionRig& rig,
    const DialGaugeSetup& setup,
    const std::function<void(const DialGaugeStation&)>& on_station = {});

/// Runs the measurement (after machine.reset with a draw of `rng`). The gauges are zeroed at the
/// reference. A gauge reads n·(p − p₀) + noise, p the true world position of its tip and p₀ that
/// at the zeroing (positive when the tip moves along the table normal). At each station the
/// command starts at the reference plus the planar move; while a reading exceeds the tolerance,
/// (z, a, b) of the command are corrected by the readings through the nominal model's sensitivity
/// (a 3×3 solve by central differences), as an operator jogs the platform (runConstrainedMotion
/// on the virtual machine). Returns the reference (station 0) and the stations. Throws
/// pkm::InvalidArgument for an invalid set-up.
[[nodiscard]] std::vector<DialGaugeStation> simulateDialGauges(HexapodVirtualMachine& machine,
                                                               const DialGaugeSetup& setup,
                                                               RandomStream& rng);

}  // namespace pkm::simulation
