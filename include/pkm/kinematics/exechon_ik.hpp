/// @file
/// @brief Exechon tripod inverse kinematics in closed form from the wrist point S (Zoppi, Zlatanov,
/// Molfino, DETC2010-28668, sec. 4), its forward map e -> S, and the Jacobian dq/dS.
/// Frames and symbols: exechon_model.hpp; e = (alpha, beta, h).
#pragma once

#include <Eigen/Core>
#include <string_view>

#include "pkm/kinematics/exechon_data.hpp"
#include "pkm/kinematics/exechon_model.hpp"

namespace pkm::kinematics {

/// Outcome of a closed-form (inverse) solve. Expected failures are statuses, never exceptions.
enum class ExechonIkStatus {
  kOk,           ///< solved
  kUnreachable,  ///< no real solution: Sx² + Sz² < hx² (S is closer to the base axis jb than |hx|)
  /// The solution is undetermined: r = sqrt(Sx² + Sz² − hx²) = 0 (with hx = 0: S on the jb axis) or
  /// t6² + Sy² = 0. Zero means below 1e-12 of the largest of |S|, |dB|, |hx|.
  kSingular,
  kInvalidInput,  ///< a non-finite input (or a zero tool direction)
};

/// "ok", "unreachable", "singular", "invalid_input".
[[nodiscard]] std::string_view toString(ExechonIkStatus status);

/// Zoppi's forward map (sec. 4.2): the wrist point S in the Zoppi frame for e = (alpha, beta, h):
/// S = hx·kA2 + hz·eh + P with P = h·eh − dB·cos(alpha)·sin(beta)·kB5. Always defined.
[[nodiscard]] Eigen::Vector3d wristPointFromParameters(const ExechonTripodGeometry& tripod,
                                                       const Eigen::Vector3d& e);

/// Zoppi's closed form (sec. 4.1, the formulas for c_alpha, s_alpha, t6, s_beta, c_beta, h) of
/// e = (alpha, beta, h) for the wrist point `zoppi_p_S` and the pose branch (delta1B, delta2B),
/// each ±1. alpha and beta are returned in (-pi, pi]. On failure *e is not modified. Throws
/// pkm::InvalidArgument if a delta is not ±1.
ExechonIkStatus parametersFromWristPoint(const ExechonTripodGeometry& tripod,
                                         const Eigen::Vector3d& zoppi_p_S,
                                         int delta1B,
                                         int delta2B,
                                         Eigen::Vector3d* e);

/// Evaluates the tripod at e for the leg working modes (deltaA, deltaC) (each ±1): S (Zoppi and
/// world), the platform pose (eq. 6), the joint points and the leg lengths (sec. 4.1: qB = |(t1,
/// t2)|, qL = |(t3 − pL·sβ − hL·cβ + δL·l12L, t2·sβ − pL·cβ + hL·sβ + dL)|) and readings.
/// data.branch gets (δ1B, δ2B) recovered from S and e (δ1B = sign(sα·Sz − cα·Sx), δ2B = sign(cβ·t6
/// − sβ·Sy); +1 where undetermined). Does not check e; never fails. Throws pkm::InvalidArgument if
/// a delta is not ±1.
void evaluateTripod(
    const ExechonModel& model, ExechonData& data, const Eigen::Vector3d& e, int deltaA, int deltaC);

/// Tripod IK for the wrist point `zoppi_p_S` (Zoppi frame, model length unit) and a given branch: e
/// by parametersFromWristPoint, then evaluateTripod. All 16 branches are available. On failure data
/// is not modified. Readings may lie outside the stroke: use the checks of exechon_checks.hpp for
/// limits. Throws pkm::InvalidArgument if the branch is invalid.
ExechonIkStatus tripodInverseKinematics(const ExechonModel& model,
                                        ExechonData& data,
                                        const Eigen::Vector3d& zoppi_p_S,
                                        const ExechonBranch& branch);

/// As above in the model's branch (branchOf(model.tripod)).
ExechonIkStatus tripodInverseKinematics(const ExechonModel& model,
                                        ExechonData& data,
                                        const Eigen::Vector3d& zoppi_p_S);

/// As above, choosing the pose branch (δ1B, δ2B) by continuity: of the four solutions, the one
/// whose e is closest to `e_near`, by 2·(1 − cos Δalpha) + 2·(1 − cos Δbeta) + (Δh /
/// characteristicLength)² (squared chords: angles are compared modulo 2·pi); δA, δC are the
/// model's. The usual choice along a path, with e_near the previous solution. kInvalidInput also
/// for a non-finite e_near.
ExechonIkStatus tripodInverseKinematicsNearest(const ExechonModel& model,
                                               ExechonData& data,
                                               const Eigen::Vector3d& zoppi_p_S,
                                               const Eigen::Vector3d& e_near);

/// Analytic Jacobians at data.e (as left by IK, FK or evaluateTripod) for data.branch's δA, δC:
/// J_q_e = d(lengths)/d(e) from the qL, qB formulas, J_S_e = d(S)/d(e) from the forward map, and
/// J_q_S = J_q_e·J_S_e⁻¹ (implicit differentiation; zero when J_S_e is singular, i.e. r = 0 or
/// t6² + Sy² = 0). Returns data.J_q_S.
const Eigen::Matrix3d& computeTripodJacobian(const ExechonModel& model, ExechonData& data);

/// Singularity proximity: σmax/σmin of data.J_q_S (call computeTripodJacobian first). J_q_S maps
/// lengths to lengths, so it is unit-free without scaling. +infinity when singular (including a
/// singular J_S_e).
[[nodiscard]] double tripodConditionNumber(const ExechonData& data);

}  // namespace pkm::kinematics
