/// @file
/// @brief The geometric errors of a hybrid machine (MXT700S parallelism paper, §2.2): the
/// position-dependent geometric errors (PDGE) of the extending axes X2 and Y2 and of the PKM, and
/// the four position-independent squareness errors szX2, sxP, syP, szP. Where each error acts in
/// the chain: pkm/kinematics/hybrid_chain.hpp.
#pragma once

#include <Eigen/Core>
#include <optional>

#include "pkm/core/units.hpp"
#include "pkm/geometry/error_grid.hpp"
#include "pkm/geometry/error_motion.hpp"
#include "pkm/geometry/error_table.hpp"
#include "pkm/kinematics/hybrid_model.hpp"

namespace pkm::kinematics {

/// The four squareness errors of the MXT700S parallelism paper (§2.2, Fig. 3; values in §4),
/// radians. Project convention (docs/conventions.md, "Signs"): a squareness is the included angle
/// between the positive directions of the two axes minus 90°, positive when that angle is larger
/// than 90°. Each value is exact when it is the only non-zero one; together they hold to first
/// order. "ISO" gives the ISO 230-1 location error (right-handed rotation of the second axis about
/// the named direction) that equals it.
struct HybridSquareness {
  /// szX2: ∠(+X2, +Y2) − 90°, in the xy plane of F (MXT700S parallelism paper: −0.034 mrad). ISO
  /// EC0X2 = −szX2 (X2 squared to the reference axis Y2).
  double sz_x2 = 0.0;
  /// sxP: ∠(+y of the X2 frame, +PZ) − 90°, in the yz plane; to first order also the vertical
  /// parallelism slope dz/dy of the PKM's Y axis to Y2 (MXT700S parallelism paper: Δα,
  /// −14.74 mrad). ISO EA0ZP = +sxP.
  double sx_p = 0.0;
  /// syP: ∠(+X2, +PZ) − 90°, in the xz plane (MXT700S parallelism paper: 4.35 mrad). ISO EB0ZP =
  /// −syP.
  double sy_p = 0.0;
  /// szP: ∠(+X2, +PY) − 90°, in the xy plane (MXT700S parallelism paper: −2.85 mrad). ISO EC0YP =
  /// +szP. To first order the horizontal parallelism slope dx/dy of PY in F is szX2 − szP.
  double sz_p = 0.0;
};

/// Rotation vector ω_X2 of F_R_X2 = exp([ω_X2]×) that realises szX2: (0, 0, −szX2), radians. The X2
/// axis direction in F is then (cos szX2, −sin szX2, 0).
[[nodiscard]] Eigen::Vector3d squarenessRotationX2(const HybridSquareness& s);

/// Rotation vector ω_P of X2_R_P = exp([ω_P]×) that realises sxP, syP, szP: (sxP, −syP, szP),
/// radians. The PKM frame P is rigid: its three axes rotate together relative to the X2 frame.
[[nodiscard]] Eigen::Vector3d squarenessRotationP(const HybridSquareness& s);

/// All geometric errors of a hybrid machine. An absent table or grid means that error is zero.
/// Each table and the grid have six columns in ErrorMotion order [dx, dy, dz, ex, ey, ez]: the
/// error motion E of the moving frame (actual = nominal · E, pkm/geometry/error_motion.hpp),
/// translations in the model length unit at the frame origin, rotations in radians.
struct GeometricErrors {
  /// Length unit of the translations and table positions; must match the machine's unit.
  LengthUnit unit = LengthUnit::kMillimetre;
  /// PDGE of X2 as functions of x2 (ISO EXX2, EYX2, EZX2, EAX2, EBX2, ECX2): error motion of the X2
  /// carriage frame, in its own axes; the translations are those of the carriage frame origin.
  std::optional<geometry::ErrorTable1d> x2;
  /// PDGE of Y2 as functions of y2 (ISO EXY2, EYY2, EZY2, EAY2, EBY2, ECY2): error motion of the
  /// table frame. It moves the work, so a positive EYY2 moves the tool by −EYY2 relative to the
  /// work.
  std::optional<geometry::ErrorTable1d> y2;
  /// The PKM's errors over its working volume: error motion of the tool frame t relative to its
  /// nominal pose in P, as a grid over the PKM command (xP, yP, zP) (MXT700S parallelism paper: the
  /// PKM's PDGE depend on all three coordinates because all its struts move together).
  std::optional<geometry::ErrorGrid3d> pkm;
  HybridSquareness squareness;  ///< the position-independent errors

  /// Throws pkm::InvalidArgument when a table or the grid does not have six columns or a squareness
  /// is not finite.
  void validate() const;
};

/// The errors at one command: what the chain consumes. Built by evaluateHybridErrors or by hand.
struct HybridErrorValues {
  geometry::ErrorMotion x2 = geometry::ErrorMotion::Zero();   ///< e_X2(x2)
  geometry::ErrorMotion y2 = geometry::ErrorMotion::Zero();   ///< e_Y2(y2)
  geometry::ErrorMotion pkm = geometry::ErrorMotion::Zero();  ///< e_P(xP, yP, zP)
  HybridSquareness squareness;
};

/// Every error multiplied by `factor` (PDGE and squareness); for sensitivity and order-of-accuracy
/// studies.
[[nodiscard]] HybridErrorValues scaled(const HybridErrorValues& values, double factor);

/// Evaluates the tables at command.x2 and command.y2 and the PKM grid at command.pkm (the
/// commanded, not the actual, positions). The tables' out-of-range policies apply (a kThrow table
/// throws pkm::InvalidArgument outside its range). Precondition: errors.validate() passes.
[[nodiscard]] HybridErrorValues evaluateHybridErrors(const GeometricErrors& errors,
                                                     const HybridCommand& command);

}  // namespace pkm::kinematics
