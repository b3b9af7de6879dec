/// @file
/// @brief Exechon tripod forward kinematics: Newton-Raphson on Zoppi's e = (alpha, beta, h) with
/// the analytic 3×3 Jacobian d(q)/d(e) and a backtracking line search. Options, summary and status
/// words are the hexapod ones (hexapod_fk.hpp).
#pragma once

#include <Eigen/Core>

#include "pkm/kinematics/exechon_data.hpp"
#include "pkm/kinematics/exechon_model.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"

namespace pkm::kinematics {

/// Solves e = (alpha, beta, h) whose leg readings (A, B, C; model length unit) equal `readings`,
/// starting from `seed_e` (the previous solution, or model.home.e), for the model's leg working
/// modes (deltaA, deltaC). Newton: J_q_e·δ = q(e) − q_target, e ← e − δ (rows: length unit; columns
/// rad, rad, length), LU with partial pivoting after dividing the two angular columns by the
/// characteristic length (unit-free pivot test against options.singular_pivot_ratio), step halving
/// (up to options.max_backtracks) until the residual norm decreases. Converged when max_i |q_i(e) −
/// q_target_i| <= options.tolerance; then one polishing step is taken unless the residual is below
/// 1e-3·tolerance (counted in iterations), as in the hexapod FK. On success data holds the solution
/// as evaluateTripod leaves it (S, platform pose, joint points, readings, the pose branch δ1B, δ2B
/// recovered from e), with alpha and beta wrapped to (-pi, pi]. On failure data holds the last
/// iterate and must not be used as a result. Statuses: kOk, kNoConvergence (iteration cap, or no
/// step reduced the residual), kSingular (J_q_e numerically singular at an iterate), kInvalidInput
/// (non-finite readings or seed). Throws pkm::InvalidArgument if `options` is invalid.
FkSummary tripodForwardKinematics(const ExechonModel& model,
                                  ExechonData& data,
                                  const ExechonLegVector& readings,
                                  const Eigen::Vector3d& seed_e,
                                  const FkOptions& options = {});

}  // namespace pkm::kinematics
