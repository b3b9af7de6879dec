/// @file
/// @brief HybridMachineModel: a PKM carried by a serial extending axis X2, over a work table on a
/// serial extending axis Y2 (MXT700S parallelism paper, §2.1: a large-volume machining robot,
/// Exechon PKM on X2/Y2). The PKM is treated as a kinematic Cartesian 3-axis machine (xP, yP, zP)
/// in its base frame P. The frames and the error chain are documented in
/// pkm/kinematics/hybrid_chain.hpp.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>

#include "pkm/core/units.hpp"

namespace pkm::kinematics {

/// The commanded positions of the five Cartesian axes, model length unit.
///
/// What the command means: X2 and the PKM's X both move the tool along x, so the tool position is
/// redundant and the command names each axis separately. The nominal tool position in the work
/// frame is the sum (hybridNominalToolPosition):
///   x = x2 + xP,   y = yP − y2,   z = zP      (plus HybridMachineModel::workOffset()).
/// y2 enters with a minus sign because Y2 moves the work table, not the tool: +y2 moves the table
/// along +y of the reference frame F, which moves the tool along −y relative to the work.
/// hybridCommandForTool turns a tool position in the work frame back into a command, for x2 and y2
/// chosen by the caller (the split rule), and hybridCommandCentred offers one split rule.
struct HybridCommand {
  double x2 = 0.0;                                ///< X2 carriage position (carries the PKM)
  double y2 = 0.0;                                ///< Y2 table position (carries the work)
  Eigen::Vector3d pkm = Eigen::Vector3d::Zero();  ///< (xP, yP, zP): PKM TCP command in P
};

/// The travel [min, max] of a serial axis, model length unit. Infinite ends mean unlimited.
struct HybridStroke {
  double min = -std::numeric_limits<double>::infinity();  ///< lowest position
  double max = std::numeric_limits<double>::infinity();   ///< highest position
};

/// The constant description of a hybrid machine (the kinematic part; the errors are in
/// GeometricErrors, pkm/kinematics/hybrid_errors.hpp). All lengths in `unit`.
struct HybridMachineModel {
  std::string name = "hybrid";
  LengthUnit unit = LengthUnit::kMillimetre;
  HybridStroke x2_stroke;  ///< X2 travel (MXT700S parallelism paper, Table 1: 4000 mm)
  HybridStroke y2_stroke;  ///< Y2 travel (MXT700S parallelism paper, Table 1: 450 mm)
  /// The PKM's Cartesian working volume: the box [pkm_min, pkm_max] of commands (xP, yP, zP) in P.
  Eigen::Vector3d pkm_min = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
  Eigen::Vector3d pkm_max = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  /// Origin of the PKM base frame P in the X2 carriage frame (0 in the MXT700S parallelism paper,
  /// which sets no offsets).
  Eigen::Vector3d X2_p_P = Eigen::Vector3d::Zero();
  /// The TCP in P when the PKM command is (0, 0, 0) (0 in the MXT700S parallelism paper: P's origin
  /// is the TCP at zero).
  Eigen::Vector3d P_p_tcp0 = Eigen::Vector3d::Zero();
  /// Origin of the work frame w in the Y2 table frame (0 in the MXT700S parallelism paper).
  Eigen::Vector3d Y2_p_work = Eigen::Vector3d::Zero();

  /// Nominal tool position in the work frame with every axis at zero:
  /// X2_p_P + P_p_tcp0 − Y2_p_work (model length unit).
  [[nodiscard]] Eigen::Vector3d workOffset() const;

  /// Throws pkm::InvalidArgument naming the field when the model is unusable: a NaN or empty
  /// stroke or working volume (min > max), or non-finite offsets.
  void validate() const;
};

/// True when x2 and y2 lie within their strokes and the PKM command within the working volume (ends
/// included). A command outside is a result, not an error; a NaN command gives false.
[[nodiscard]] bool hybridWithinLimits(const HybridMachineModel& model,
                                      const HybridCommand& command);

/// The nominal tool position in the work frame (no errors; MXT700S parallelism paper, eq. 3 with
/// every error zero): (x2 + xP, yP − y2, zP) + model.workOffset(), model length unit.
[[nodiscard]] Eigen::Vector3d hybridNominalToolPosition(const HybridMachineModel& model,
                                                        const HybridCommand& command);

/// The command that puts the tool nominally at `work_p_tool` (work frame, model length unit) with
/// X2 at `x2` and Y2 at `y2`: the PKM takes the rest, pkm = work_p_tool − workOffset() − (x2, −y2,
/// 0). Inverse of hybridNominalToolPosition for the given x2, y2. Limits are not checked
/// (hybridWithinLimits).
[[nodiscard]] HybridCommand hybridCommandForTool(const HybridMachineModel& model,
                                                 const Eigen::Vector3d& work_p_tool,
                                                 double x2,
                                                 double y2);

/// A split rule: choose x2 and y2 so that the PKM's xP and yP are at the centre of its working
/// volume (0, clamped to the volume, when a side is unbounded), with x2 and y2 clamped to their
/// strokes; the PKM takes the rest (hybridCommandForTool). The PKM part may leave its working
/// volume when the target is out of reach; check with hybridWithinLimits. Precondition:
/// model.validate() passes and work_p_tool is finite (pkm::InvalidArgument otherwise).
[[nodiscard]] HybridCommand hybridCommandCentred(const HybridMachineModel& model,
                                                 const Eigen::Vector3d& work_p_tool);

}  // namespace pkm::kinematics
