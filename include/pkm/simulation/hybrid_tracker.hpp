/// @file
/// @brief A laser tracker on the work table of a hybrid machine (MXT700S parallelism paper): at
/// random commands of the five axes (x2, y2 and the PKM's xP, yP, zP) it reads an SMR on the tool,
/// in its own frame. The data of the identification of the four squareness errors (docs/formats.md,
/// "Hybrid tracker files").
#pragma once

#include <string>
#include <vector>

#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/simulation/hybrid_virtual_machine.hpp"
#include "pkm/simulation/laser_tracker.hpp"
#include "pkm/simulation/random.hpp"

namespace pkm::simulation {

/// The set-up of a tracker measurement on a hybrid machine. Frames: the work frame w.
struct HybridTrackerSetup {
  std::string name = "hybrid-tracker";                ///< names the random stream and the file
  int count = 0;                                      ///< random commands, ≥ 1
  Eigen::Vector2d x2 = Eigen::Vector2d::Zero();       ///< [min, max] of the X2 command, mm
  Eigen::Vector2d y2 = Eigen::Vector2d::Zero();       ///< [min, max] of the Y2 command, mm
  Eigen::Vector3d pkm_min = Eigen::Vector3d::Zero();  ///< PKM command box (P frame), mm
  Eigen::Vector3d pkm_max = Eigen::Vector3d::Zero();
  /// SMR centre in the tool frame t (P's axes at the TCP), mm.
  Eigen::Vector3d smr_offset = Eigen::Vector3d::Zero();
  /// The tracker's placement in the work frame, work_T_tracker (rigid; part of the truth).
  geometry::RigidTransform work_T_tracker = geometry::RigidTransform::Identity();
  TrackerNoise noise;
  /// Throws pkm::InvalidArgument for an empty name, count < 1, an inverted or non-finite range,
  /// a non-finite offset, invalid noise or a placement that is not rigid.
  void validate() const;
};

/// One reading.
struct HybridTrackerReading {
  kinematics::HybridCommand command;                   ///< the commanded axes
  Eigen::Vector3d measured = Eigen::Vector3d::Zero();  ///< SMR, tracker frame, with noise
  Eigen::Vector3d truth = Eigen::Vector3d::Zero();     ///< SMR, tracker frame, exact
};

/// Runs the measurement: `count` commands drawn uniformly from the ranges that lie within the
/// machine's strokes and working volume and that the machine reaches (rejected draws are redrawn,
/// at most 200·count draws), the SMR read with the tracker noise (from `rng`). Throws
/// pkm::InvalidArgument for an invalid set-up or too few reachable commands.
[[nodiscard]] std::vector<HybridTrackerReading> simulateHybridTracker(
    HybridVirtualMachine& machine, const HybridTrackerSetup& setup, RandomStream& rng);

}  // namespace pkm::simulation
