/// @file
/// @brief Per-configuration limit checks of an Exechon: leg stroke, tripod angles alpha and beta,
/// wrist C and A ranges, and singularity proximity, each naming the leg or limit with its margin.
/// Violations and status words are those of the hexapod checks (hexapod_checks.hpp).
#pragma once

#include <string_view>
#include <vector>

#include "pkm/kinematics/exechon_data.hpp"
#include "pkm/kinematics/exechon_model.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"
#include "pkm/kinematics/hexapod_checks.hpp"

namespace pkm::kinematics {

/// Results of the Exechon checks. Margins follow docs/conventions.md: >= 0 while a limit holds,
/// +infinity when it is disabled; lengths in the model unit, angles in rad.
struct ExechonCheckResult {
  /// "ok", or the status word of the solve that failed (IK: "unreachable", "singular",
  /// "invalid_input"; FK: "no_convergence", "singular", "invalid_input"); then no limit was
  /// checked.
  std::string_view solver_status = "ok";
  ExechonLegVector readings = ExechonLegVector::Zero();       ///< legs A, B, C
  ExechonLegVector stroke_margin = ExechonLegVector::Zero();  ///< min(reading − min, max − reading)
  double alpha = 0.0, beta = 0.0;                             ///< rad
  double alpha_margin = 0.0, beta_margin = 0.0;               ///< rad
  double c = 0.0, a = 0.0;                                    ///< wrist readings, rad
  double c_margin = 0.0, a_margin = 0.0;                      ///< rad
  bool wrist_at_pole = false;     ///< tool along the C axis: C undefined (not a violation)
  double condition_number = 0.0;  ///< tripodConditionNumber (σmax/σmin of dq/dS)
  double condition_margin = 0.0;  ///< max_condition − condition_number
  /// In the order stroke (items "leg A".."leg C"), degenerate (zero-length leg), joint_angle
  /// ("alpha", "beta", "wrist C", "wrist A"), singular ("jacobian").
  std::vector<LimitViolation> violations;

  [[nodiscard]] bool ok() const { return solver_status == "ok" && violations.empty(); }
  /// solver_status when the solve failed, else "ok" or the status word of the first violation.
  [[nodiscard]] std::string_view status() const;
};

/// Checks the configuration held in `data` (as left by a successful IK, FK or
/// evaluateConfiguration). Computes the tripod Jacobian into data.
[[nodiscard]] ExechonCheckResult checkConfiguration(const ExechonModel& model, ExechonData& data);

/// Tool IK (model branch, wrist nearest home) followed by checkConfiguration.
[[nodiscard]] ExechonCheckResult checkToolPose(const ExechonModel& model,
                                               ExechonData& data,
                                               const ExechonToolPose& target);

/// Tool IK by continuity from `previous` followed by checkConfiguration.
[[nodiscard]] ExechonCheckResult checkToolPose(const ExechonModel& model,
                                               ExechonData& data,
                                               const ExechonToolPose& target,
                                               const ExechonConfiguration& previous);

/// Tool FK from `seed` followed by checkConfiguration. Throws pkm::InvalidArgument if `options` is
/// invalid.
[[nodiscard]] ExechonCheckResult checkJoints(const ExechonModel& model,
                                             ExechonData& data,
                                             const ExechonJoints& joints,
                                             const ExechonConfiguration& seed,
                                             const FkOptions& options = {});

}  // namespace pkm::kinematics
