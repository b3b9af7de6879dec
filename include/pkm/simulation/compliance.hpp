/// @file
/// @brief Gravity self-weight deflection and passive-joint clearance of the virtual machines
/// (environment.hpp, ComplianceEnvironment; docs/simulation-errors.md, "Structure: compliance
/// (gravity sag) and joint clearance"). Gravity acts along −z of the work (world) frame.
#pragma once

#include <Eigen/Core>

#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/kinematics/exechon_data.hpp"
#include "pkm/kinematics/exechon_model.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"
#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_model.hpp"
#include "pkm/simulation/environment.hpp"

namespace pkm::simulation {

/// Standard acceleration of gravity g_n, m/s² (3rd CGPM, 1901).
inline constexpr double kStandardGravity = 9.80665;

/// The sag of an axis's structure where it carries the load.
struct AxisDeflection {
  double sag_mm = 0.0;     ///< downward deflection δ, mm
  double slope_rad = 0.0;  ///< slope θ = dδ/dx along the direction of growing overhang/position
};

/// δ and θ of `sag` at the axis command `command_mm` (AxisSag's formulas). A cantilever whose
/// overhang L(q) ≤ 0 and a span load outside [0, length] give zero; kNone gives zero. Throws
/// pkm::InvalidArgument when `sag` is invalid or the command is not finite.
[[nodiscard]] AxisDeflection axisDeflection(const AxisSag& sag, double command_mm);

/// The tool pose work_T_tool of a machine whose axis carrying the tool sags by `d`: the axis's
/// structure turns by φ = θ·(ẑ × e) about `pivot` (e the unit direction of growing overhang, work
/// frame; ẑ × e tilts it nose down) and drops by δ·|ẑ × e| (the part of gravity across the axis
/// bends it): p → pivot + Rot(φ)·(p − pivot) − δ·|ẑ × e|·ẑ, R → Rot(φ)·R. `pose` itself for zero
/// deflection.
[[nodiscard]] geometry::RigidTransform sagCarryingTool(const geometry::RigidTransform& pose,
                                                       const AxisDeflection& d,
                                                       const Eigen::Vector3d& direction,
                                                       const Eigen::Vector3d& pivot);

/// The same for an axis that carries the WORK (a table): the work frame sags, so the tool seen
/// from it moves the opposite way, work_T_tool → S⁻¹·work_T_tool with S the sag motion above.
[[nodiscard]] geometry::RigidTransform sagCarryingWork(const geometry::RigidTransform& pose,
                                                       const AxisDeflection& d,
                                                       const Eigen::Vector3d& direction,
                                                       const Eigen::Vector3d& pivot);

/// The axial forces of a hexapod's struts under gravity, N, compression positive (a strut
/// pushing the platform away from its base joint), at the pose of `data` after
/// kinematics::inverseKinematics with `model` (unit mm). The platform's statics
///   Σ C_i·u_i + F = 0,  Σ C_i·(r_i × u_i) + M = 0,  i.e. C = −J⁻ᵀ·w
/// with u_i the strut's unit vector from the base to the platform joint, r_i the platform joint
/// relative to the TCP (world), J = data.J_q_x's rows [u_iᵀ, (r_i × u_i)ᵀ], and w = (F, M) the
/// gravity wrench about the TCP: the platform's weight m_p·g at its centre of mass
/// (HexapodCompliance::platform_com_mm, platform frame) and the share η·m_s·g of every strut's
/// weight at its platform joint. Throws pkm::InvalidArgument when `compliance` is invalid or J is
/// singular.
[[nodiscard]] kinematics::StrutVector hexapodStrutLoads(const kinematics::HexapodModel& model,
                                                        const kinematics::HexapodData& data,
                                                        const HexapodCompliance& compliance);

/// The change of a leg's joint distance under the axial force `load_n` (compression positive),
/// mm: −load/k (k in N/µm, so −load_n/(1000·k)) minus the joint clearance c taken up in the
/// force's direction, c·side with side = +1 under compression and −1 under tension. `side` keeps
/// the previous side when the load is exactly 0 and is updated otherwise.
[[nodiscard]] double legDeflection(double load_n,
                                   double stiffness_n_per_um,
                                   double clearance_mm,
                                   int& side);

/// The axial forces of an Exechon's legs A, B, C under the head's weight, N, compression
/// positive, by virtual work (the joints' constraint forces do no work): C_i = m·g·∂z_c/∂q_i,
/// z_c the height (world z) of the centre of mass ExechonCompliance::head_com_mm (tool frame) at
/// the tool FK of `model` for `joints` with the wrist held, the derivative by central differences
/// (±0.01 mm) of toolForwardKinematics seeded with `seed`. Throws pkm::InvalidArgument for an
/// invalid compliance or when an FK does not converge.
[[nodiscard]] Eigen::Vector3d exechonLegLoads(const kinematics::ExechonModel& model,
                                              const kinematics::ExechonJoints& joints,
                                              const kinematics::ExechonConfiguration& seed,
                                              const kinematics::FkOptions& fk,
                                              const ExechonCompliance& compliance);

/// `joints` with each leg reading changed by legDeflection(C_i, k, c, side) for the loads of
/// exechonLegLoads (side from the load's sign: the clearance taken up in its direction). Throws
/// as exechonLegLoads.
[[nodiscard]] kinematics::ExechonJoints exechonDeflectedJoints(
    const kinematics::ExechonModel& model,
    const kinematics::ExechonJoints& joints,
    const kinematics::ExechonConfiguration& seed,
    const kinematics::FkOptions& fk,
    const ExechonCompliance& compliance);

}  // namespace pkm::simulation
