/// @file
/// @brief ExechonModel: the constant description of an Exechon machine — a 2UPR-SPR tripod (Zoppi,
/// Zlatanov, Molfino, "Kinematics analysis of the Exechon tripod", ASME IDETC 2010, DETC2010-28668)
/// carrying a spherical C/A wrist. Model/Data split: the workspace is ExechonData.
///
/// Frames (docs/conventions.md names):
/// - **Zoppi frame** (O, ib, jb, kb): the tripod's base frame of the paper. jb is the common first
///   axis of legs A and C; O is the projection of leg B's base joint centre P1B on it; base joint
///   centres P1A = (0, dA, 0), P1B = (dB, 0, 0), P1C = (0, dC, 0).
/// - **Platform frame** (P, i, j, k): i = kA2 (normal of the plane of legs A and C), j = kB5 (axis
/// of
///   leg B's platform revolute), k = eh = kA2 × kB5; P is the projection of P5B on that plane. The
///   rows of Zoppi's eq. (6) are i, j, k. For h > 0 the platform lies on the +k side of the base
///   axis, so +k points away from the base.
/// - **World frame**: the machine's frame; world_p = world_T_zoppi · zoppi_p.
/// The wrist point S (where the C and A axes meet) is (hx, 0, hz) in the platform frame.
#pragma once

#include <Eigen/Core>
#include <array>
#include <limits>
#include <string>

#include "pkm/core/units.hpp"
#include "pkm/geometry/rigid_transform.hpp"

namespace pkm::kinematics {

/// Number of tripod legs of an Exechon: A, B, C (actuated lengths q1, q2, q3).
inline constexpr int kExechonLegs = 3;

/// Strut lengths or readings of legs A, B, C (index 0, 1, 2), model length unit.
using ExechonLegVector = Eigen::Vector3d;

/// Zoppi's tripod geometry (DETC2010-28668, sec. 3 and Table 1) and the branch (working/assembly
/// mode) the machine is built in. Lengths in the model's unit.
struct ExechonTripodGeometry {
  double dA = 0.0;  ///< jb coordinate of leg A's base joint centre P1A = (0, dA, 0)
  double dB = 0.0;  ///< ib coordinate of leg B's base S-joint centre P1B = (dB, 0, 0); must be != 0
  double dC = 0.0;  ///< jb coordinate of leg C's base joint centre P1C = (0, dC, 0)
  double l12A = 0.0;  ///< leg A: distance between its base U-joint's two axes (0: ideal U)
  double l12C = 0.0;  ///< leg C: same as l12A
  /// Leg B's base S joint as three revolutes whose axes need not meet (the base-joint axis offsets
  /// of Lopez-Custodio, Dai, Fu, Jin, J. Mech. Robot. 12(2) 021109, 2020): R1 parallel to jb
  /// through P1B, R2 ⟂ R1, R3 = the leg's own axis ⟂ R2. l12B is the distance from R1 to R2 along
  /// their common normal, positive towards the platform; l23B the distance from R2 to the leg axis,
  /// positive towards +jb (0, 0: an ideal S joint and Zoppi's closed form; otherwise the tripod
  /// kinematics solve leg B numerically, docs/conventions.md "Leg B's base-joint offsets").
  double l12B = 0.0;
  double l23B = 0.0;  ///< see l12B
  double pA = 0.0;    ///< j coordinate of leg A's platform joint P4A (platform frame)
  double pB = 0.0;    ///< i coordinate of leg B's platform joint P5B (platform frame)
  double pC = 0.0;    ///< j coordinate of leg C's platform joint P4C (platform frame)
  double hA = 0.0;    ///< offset of leg A's platform revolute axis from the plane of legs A and C
  double hC = 0.0;    ///< offset of leg C's platform revolute axis from that plane
  double hx = 0.0;    ///< i coordinate of the wrist point S in the platform frame
  double hz = 0.0;    ///< k coordinate of the wrist point S in the platform frame
  /// Branch signs, each +1 or -1 (Zoppi's δ1B, δ2B: the four platform poses for one S; δA, δC: the
  /// working modes of legs A and C, the side of the U-joint offset l12). All 16 combinations exist.
  int delta1B = 1;  ///< δ1B: side of the base axis the platform pose lies on (sign of r)
  int delta2B =
      1;  ///< δ2B: sign of the in-plane orientation solution (cos beta = δ2B·t6/|(t6, Sy)|)
  int deltaA = 1;  ///< δA: working mode of leg A (its length uses +δA·l12A)
  int deltaC = 1;  ///< δC: working mode of leg C (its length uses +δC·l12C)
};

/// One actuated leg. reading + length_offset = Zoppi's geometric length q (joint centre distance).
struct ExechonLeg {
  double length_offset = 0.0;                                     ///< model length unit
  double min_reading = -std::numeric_limits<double>::infinity();  ///< lowest reading (stroke)
  double max_reading = std::numeric_limits<double>::infinity();   ///< highest reading (stroke)
};

/// A closed interval [min, max] of an angle in radians; ±infinity (the default) disables a side.
struct AngleRange {
  double min = -std::numeric_limits<double>::infinity();  ///< rad
  double max = std::numeric_limits<double>::infinity();   ///< rad
  /// Signed distance to the nearer end: min(value − min, max − value); +infinity when unlimited.
  [[nodiscard]] double margin(double value) const;
};

/// Angle limits. alpha and beta are Zoppi's tripod angles; c and a are the wrist axis readings.
struct ExechonLimits {
  AngleRange alpha;  ///< rotation of the legs-A/C plane about the base axis jb, rad
  AngleRange beta;   ///< in-plane platform angle (between kB5 and jb), rad
  AngleRange c;      ///< wrist C reading, rad
  AngleRange a;      ///< wrist A reading, rad
};

/// A spherical C/A wrist centred at the wrist point S.
///
/// Geometric angles from readings: θC = c_sign·C + c0, θA = a_sign·A + a0 (rad). The tool frame is
///   platform_R_tool = W · Rz(θC) · Rx(θA),   W = [a_axis, c_axis × a_axis, c_axis] (platform
///   frame),
/// so the C axis is c_axis (platform-fixed), the A axis is W·Rz(θC)·x (it turns with C), and the
/// tool direction (tool z) is platform_R_tool·ẑ = W·(sin θC·sin θA, −cos θC·sin θA, cos θA). At θC
/// = θA = 0 the tool points along c_axis; the default c_axis = +k points away from the base. The
/// tool point is world_p_S + tool_length·tool direction. θA = 0 is the pole where C is undefined.
struct ExechonWrist {
  Eigen::Vector3d c_axis =
      Eigen::Vector3d::UnitZ();  ///< C axis, platform frame (normalised by pkm)
  Eigen::Vector3d a_axis =
      Eigen::Vector3d::UnitX();  ///< A axis at θC = 0, platform frame; ⟂ c_axis
  double c0 = 0.0;               ///< zero offset of C, rad (θC = c_sign·C + c0)
  double a0 = 0.0;               ///< zero offset of A, rad (θA = a_sign·A + a0)
  int c_sign = 1;                ///< +1 or -1: sense of the C reading about c_axis
  int a_sign = 1;                ///< +1 or -1: sense of the A reading about the A axis
  double tool_length =
      0.0;  ///< from S to the tool point along the tool direction, model length unit
};

/// A configuration in joint-like coordinates: Zoppi's tripod parameters e = (alpha, beta, h)
/// (alpha, beta in rad, h in the model length unit; the forward map e -> S is unique) and the wrist
/// readings C, A (rad). Used for the home configuration, FK seeds and the "previous solution" of
/// continuity.
struct ExechonConfiguration {
  Eigen::Vector3d e = Eigen::Vector3d::Zero();  ///< (alpha, beta, h)
  double c = 0.0;                               ///< wrist C reading, rad
  double a = 0.0;                               ///< wrist A reading, rad
};

/// The home configuration (FK seed, IK reference for the wrist branch).
using ExechonHome = ExechonConfiguration;

/// The constant description of an Exechon machine. Lengths in `unit`, angles in radians.
struct ExechonModel {
  std::string name = "exechon";
  LengthUnit unit = LengthUnit::kMillimetre;
  ExechonTripodGeometry tripod;
  std::array<ExechonLeg, kExechonLegs> legs{};  ///< A, B, C
  ExechonLimits limits;
  ExechonWrist wrist;
  /// Pose of Zoppi's base frame in the machine's world frame (identity: world = Zoppi frame).
  geometry::RigidTransform world_T_zoppi = geometry::RigidTransform::Identity();
  ExechonHome home;
  /// Largest allowed condition number of dq/dS (unit-free; see exechon_ik.hpp).
  double max_condition = 1e3;

  /// Characteristic length: max(|dA|, |dB|, |dC|), used for relative tolerances. > 0 when valid.
  [[nodiscard]] double characteristicLength() const;

  /// Throws pkm::InvalidArgument naming the field when the model is unusable: non-finite values,
  /// dB = 0, dA = dC, a branch sign not ±1, an empty stroke or angle range, zero or
  /// non-perpendicular wrist axes, a wrist sign not ±1, max_condition <= 1, world_T_zoppi not
  /// rigid, or a home configuration that is degenerate (zero-length leg) or singular.
  void validate() const;
};

}  // namespace pkm::kinematics
