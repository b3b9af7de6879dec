/// @file
/// @brief Hexapod forward kinematics: Newton-Raphson on SO(3) with a backtracking line search.
#pragma once

#include <string>
#include <string_view>

#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::kinematics {

/// Outcome of a forward-kinematics solve.
enum class FkStatus {
  kOk,             ///< converged: every strut residual <= FkOptions::tolerance
  kNoConvergence,  ///< iteration cap reached or no step reduced the residual
  kSingular,       ///< the strut Jacobian is (numerically) singular at an iterate
  kInvalidInput,   ///< non-finite reading or seed
  /// Converged, but to a pose of another assembly mode than the seed's: the strut Jacobian's
  /// determinant changed sign on the way (a singularity was crossed). A true pose from a far
  /// seed, or a wrong one: never reported as kOk. (Hexapod FK only.)
  kOtherBranch,
};

/// "ok", "no_convergence", "singular", "invalid_input", "other_branch".
[[nodiscard]] std::string_view toString(FkStatus status);

/// Options of forwardKinematics.
struct FkOptions {
  /// Convergence when max_i |reading_i(pose) − reading_i| <= tolerance (model length unit).
  /// LinuxCNC genhexkins `convergence-criterion` (default 1e-9).
  double tolerance = 1e-9;
  /// Largest number of Newton steps (genhexkins `limit-iterations`, default 120).
  int max_iterations = 120;
  /// Step halvings tried when a full Newton step does not reduce the residual norm.
  int max_backtracks = 12;
  /// A pivot of the LU factorisation smaller than this fraction of the largest one means singular.
  double singular_pivot_ratio = 1e-12;
  /// Trust region of one Newton step (hexapod FK): at most this many characteristic lengths of
  /// translation (HexapodModel::characteristicLength) and this many radians of rotation; a longer
  /// step is shortened, keeping its direction. Far seeds take more, shorter steps and stay in
  /// their own assembly mode instead of jumping to another.
  double max_step_translation = 0.5;
  double max_step_rotation = 0.25;  ///< rad
  /// A seed whose strut readings differ from the target's by more than this many characteristic
  /// lengths is a cold start: it is solved by continuation, in stages of at most this change of
  /// the readings, each stage seeded by the previous one (iterations and max_iterations count
  /// per stage; `iterations` reports their sum).
  double continuation_step = 0.3;

  /// True when every field is usable; otherwise false with the reason in *why (if given).
  [[nodiscard]] bool isValid(std::string* why = nullptr) const;
};

/// What a forward-kinematics solve did.
struct FkSummary {
  FkStatus status = FkStatus::kInvalidInput;
  int iterations = 0;         ///< Newton steps taken
  int backtracks = 0;         ///< step halvings over all iterations
  double max_residual = 0.0;  ///< max_i |residual_i| at the returned pose (model length unit)
  [[nodiscard]] bool ok() const { return status == FkStatus::kOk; }
};

/// Solves the platform TCP pose whose strut readings equal `readings`, starting from `seed` (the
/// previous servo-cycle pose, or home). Newton-Raphson on (p, R): J_q_x·δ = r(x), p ← p − δp, R ←
/// exp(−[δθ]×)·R (a true SO(3) update, unlike genhexkins' additive angle update), LU with partial
/// pivoting, and step halving when the full step does not reduce |r|. A full step is corrected for
/// its second-order strut residual (the legs' curvature, from the same factorisation), so a seed
/// close to the answer lands within O(|δ|³) in one iteration. Once every residual is within
/// the tolerance, one more step is taken unless the residual is already below 1e-3·tolerance (so
/// the pose, not only the struts, is accurate to the tolerance; it is counted in iterations). Steps
/// are limited to the options' trust region; a far seed is solved by continuation along the
/// readings (FkOptions::continuation_step); a solution whose strut Jacobian determinant has another
/// sign than at the seed is kOtherBranch (see FkStatus). On
/// success data.pose holds the pose, with angles chosen nearest to the seed's (continuous along a
/// path); data's leg quantities match it. On failure data.pose holds the last iterate and must not
/// be used as a result. Throws pkm::InvalidArgument if `options` is invalid.
FkSummary forwardKinematics(const HexapodModel& model,
                            HexapodData& data,
                            const StrutVector& readings,
                            const PoseRpy& seed,
                            const FkOptions& options = {});

/// As above, with the seed given as the TCP position and platform rotation (world frame), as a
/// servo loop keeps them from its last solution (data.world_p_tcp, data.world_R_platform): no
/// roll-pitch-yaw conversion of the seed. With `rpy_near` (rad), data.pose.rpy is set to the
/// angles nearest to it (the last solution's, for continuity); without it (nullptr) the angles
/// are not computed (data.pose.rpy is left as it was; the rotation is data.world_R_platform), for
/// callers that convert them elsewhere. Throws as above.
FkSummary forwardKinematics(const HexapodModel& model,
                            HexapodData& data,
                            const StrutVector& readings,
                            const Eigen::Vector3d& world_p_seed,
                            const Eigen::Matrix3d& world_R_seed,
                            const Eigen::Vector3d* rpy_near,
                            const FkOptions& options = {});

/// forwardKinematics for one model and one set of options, set up once: the options are checked
/// and the model's characteristic length taken at construction, so that a servo loop's solve()
/// does only the solving (the free functions build one per call). The same algorithm and results
/// as forwardKinematics. `model` must outlive the solver and stay unchanged while it is used.
class HexapodFkSolver {
 public:
  /// Throws pkm::InvalidArgument if `options` is invalid.
  explicit HexapodFkSolver(const HexapodModel& model, const FkOptions& options = {});

  /// forwardKinematics(model, data, readings, world_p_seed, world_R_seed, rpy_near, options).
  FkSummary solve(HexapodData& data,
                  const StrutVector& readings,
                  const Eigen::Vector3d& world_p_seed,
                  const Eigen::Matrix3d& world_R_seed,
                  const Eigen::Vector3d* rpy_near = nullptr) const;

  [[nodiscard]] const HexapodModel& model() const { return model_; }
  [[nodiscard]] const FkOptions& options() const { return options_; }

 private:
  struct Pose {
    Eigen::Vector3d p;
    Eigen::Matrix3d R;
  };
  /// The common case of a servo loop, a near seed: one corrected Newton step (and the polishing
  /// step when it is due), with data holding the seed's legs, r0 their residual against the
  /// readings and gap its largest magnitude (detail::computeLegsResidual). Returns false, with
  /// data and x in an unspecified state, whenever the general solver would do anything else.
  bool solveNear(HexapodData& data,
                 const StrutVector& readings,
                 const StrutVector& r0,
                 double gap,
                 Pose& x,
                 FkSummary& out) const;
  /// The general solver (continuation, damped Newton) from x, with data holding x's legs.
  FkSummary solveGeneral(HexapodData& data, const StrutVector& readings, Pose& x) const;

  friend struct HexapodFkSolverTestPeer;  // tests compare solveNear with solveGeneral

  const HexapodModel& model_;
  FkOptions options_;
  double length_ = 1.0;           ///< model_.characteristicLength()
  double inv_length_ = 1.0;       ///< 1 / length_
  double max_translation_ = 0.0;  ///< options_.max_step_translation · length_
};

}  // namespace pkm::kinematics
