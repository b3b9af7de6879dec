/// @file
/// @brief The kinematic error chain of the hybrid machine: nominal and actual pose of the tool in
/// the work frame by exact composition of homogeneous transforms (HTMs), the volumetric error Δp =
/// actual − nominal (MXT700S parallelism paper, eq. 3), and its first-order (small-angle) linear
/// model.
///
/// Reconstruction of §2.2 of the MXT700S parallelism paper (its eqs. 1–2 are missing from the text
/// and eq. 3 is garbled; what follows is rebuilt from the frames the text describes and is the
/// project's definition):
///
/// Frames
/// - F  reference frame, fixed to the bed. Origin: the X2 and Y2 carriage frame origins at
///      x2 = y2 = 0 (with the MXT700S parallelism paper's zero offsets, the TCP with every axis at
///      zero). y along the Y2 axis (+y = the direction the table moves for +y2); x perpendicular to
///      y in the plane of the X2 and Y2 axes (the X2 axis lies in F's xy plane); z = x × y.
/// - Y2 the Y2 carriage (work table) frame; F at y2 = 0 without errors.
/// - w  the work frame, fixed to the table (Y2_p_work from its origin, axes parallel).
/// - X2 the X2 carriage frame (carries the PKM); its x axis is the X2 direction of travel.
/// - P  the PKM's base (kinematic) frame, fixed to the X2 carriage.
/// - t  the tool frame at the TCP (orientation: that of P; the PKM's wrist is not modelled).
///
/// Local HTMs, actual (nominal: every error zero). Trans(v) = translationTransform, Rot(ω) =
/// exp([ω]×), E(e) = errorMotionHtm(e) (pkm/geometry/error_motion.hpp):
///   F_T_Y2 = Trans(y2·ŷ) · E(e_Y2(y2))
///   Y2_T_w = Trans(Y2_p_work)
///   F_T_X2 = Rot(ω_X2) · Trans(x2·x̂) · E(e_X2(x2)),   ω_X2 = (0, 0, −szX2)
///   X2_T_P = Trans(X2_p_P) · Rot(ω_P),                ω_P = (sxP, −syP, szP)
///   P_T_t  = Trans(P_p_tcp0 + p) · E(e_P(p)),          p = (xP, yP, zP), the PKM command
/// composed as (MXT700S parallelism paper, eq. 3)
///   w_T_t  = (F_T_Y2 · Y2_T_w)⁻¹ · F_T_X2 · X2_T_P · P_T_t.
/// So: each PDGE multiplies its axis's nominal motion on the right (it is the error motion of the
/// moving frame, in that frame's axes, about that frame's origin); szX2 rotates the X2 axis and
/// carriage about F's z before the X2 motion; sxP, syP, szP rotate P rigidly about its origin
/// relative to the X2 carriage. The signs make each squareness the project's included-angle
/// squareness (see HybridSquareness): e.g. moving X2 alone by x moves the tool, exactly, by
/// (x·cos szX2, −x·sin szX2, 0), i.e. Δy ≈ −szX2·x.
///
/// First-order model (hybridVolumetricErrorLinear), in the work frame, with δ and ε the translation
/// and rotation parts of each error motion:
///   Δp ≈ δ_P + ω_P × q + δ_X2 + ε_X2 × r + ω_X2 × (x2·x̂ + r) − δ_Y2 − ε_Y2 × s
///   q = P_p_tcp0 + p        (TCP in P),
///   r = X2_p_P + q          (TCP in the X2 carriage frame),
///   s = x2·x̂ + r − y2·ŷ     (TCP in the Y2 table frame; = nominal tool position + Y2_p_work).
/// It neglects every product of two errors, so exact − linear = O(|error|²).
#pragma once

#include <Eigen/Core>

#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/kinematics/hybrid_errors.hpp"
#include "pkm/kinematics/hybrid_model.hpp"

namespace pkm::kinematics {

/// The local HTMs of the chain at one command, and their composition (see the file comment).
/// Each X_T_Y maps coordinates in frame Y to coordinates in frame X.
struct HybridChain {
  /// Y2 table frame in F.
  geometry::RigidTransform F_T_Y2 = geometry::RigidTransform::Identity();
  /// Work frame in the table frame.
  geometry::RigidTransform Y2_T_w = geometry::RigidTransform::Identity();
  /// X2 carriage frame in F.
  geometry::RigidTransform F_T_X2 = geometry::RigidTransform::Identity();
  /// PKM base frame in the X2 frame.
  geometry::RigidTransform X2_T_P = geometry::RigidTransform::Identity();
  /// Tool frame in the PKM base frame.
  geometry::RigidTransform P_T_t = geometry::RigidTransform::Identity();
  /// Tool in the work frame (eq. 3).
  geometry::RigidTransform w_T_t = geometry::RigidTransform::Identity();
};

/// The chain at `command` with the errors `values` (exact HTMs; pass HybridErrorValues{} for the
/// nominal chain). Throws pkm::InvalidArgument for a non-finite command.
[[nodiscard]] HybridChain hybridChain(const HybridMachineModel& model,
                                      const HybridErrorValues& values,
                                      const HybridCommand& command);

/// The nominal work_T_tool: translation hybridNominalToolPosition(model, command), identity
/// rotation. Throws pkm::InvalidArgument for a non-finite command.
[[nodiscard]] geometry::RigidTransform hybridNominalPose(const HybridMachineModel& model,
                                                         const HybridCommand& command);

/// The actual work_T_tool with the errors `values`: hybridChain(...).w_T_t.
[[nodiscard]] geometry::RigidTransform hybridActualPose(const HybridMachineModel& model,
                                                        const HybridErrorValues& values,
                                                        const HybridCommand& command);

/// As above with the errors evaluated at the command (evaluateHybridErrors).
[[nodiscard]] geometry::RigidTransform hybridActualPose(const HybridMachineModel& model,
                                                        const GeometricErrors& errors,
                                                        const HybridCommand& command);

/// The volumetric error Δp = p − p̄ (MXT700S parallelism paper, eq. 3): actual minus nominal tool
/// position, in the work frame, model length unit; exact (no small-angle approximation).
[[nodiscard]] Eigen::Vector3d hybridVolumetricError(const HybridMachineModel& model,
                                                    const HybridErrorValues& values,
                                                    const HybridCommand& command);

/// As above with the errors evaluated at the command (evaluateHybridErrors).
[[nodiscard]] Eigen::Vector3d hybridVolumetricError(const HybridMachineModel& model,
                                                    const GeometricErrors& errors,
                                                    const HybridCommand& command);

/// The first-order model of Δp (file comment): linear in all errors, exact − linear = O(|error|²).
/// Work frame, model length unit. Throws pkm::InvalidArgument for a non-finite command.
[[nodiscard]] Eigen::Vector3d hybridVolumetricErrorLinear(const HybridMachineModel& model,
                                                          const HybridErrorValues& values,
                                                          const HybridCommand& command);

/// As above with the errors evaluated at the command (evaluateHybridErrors).
[[nodiscard]] Eigen::Vector3d hybridVolumetricErrorLinear(const HybridMachineModel& model,
                                                          const GeometricErrors& errors,
                                                          const HybridCommand& command);

}  // namespace pkm::kinematics
