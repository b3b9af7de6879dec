#include "pkm/kinematics/hexapod_fk.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "kinematics/detail/hexapod_legs.hpp"
#include "kinematics/detail/newton.hpp"
#include "kinematics/detail/solve6.hpp"
#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::kinematics {
namespace {
/// Strut tolerance of the intermediate stages of a continuation, × the characteristic length.
constexpr double kStageTolerance = 1e-6;

/// Strut-space step δ = (δp, δθ) for the residual r = delta on input, from a factorisation of the
/// scaled Jacobian, shortened to the options' trust region. Returns whether it was shortened.
bool scaledStep(const detail::Lu6& lu,
                double inv_length,
                double max_translation,
                double max_rotation,
                StrutVector& delta) {
  detail::substitute6(lu, delta);
  delta.tail<3>() *= inv_length;
  // Well inside the trust region (the common case) the norms are not needed: squared lengths
  // with a margin of rounding decide it.
  constexpr double kInside = 1.0 - 1e-9;
  if (delta.head<3>().squaredNorm() < kInside * max_translation * max_translation &&
      delta.tail<3>().squaredNorm() < kInside * max_rotation * max_rotation)
    return false;
  const double shrink = std::max(
      {1.0, delta.head<3>().norm() / max_translation, delta.tail<3>().norm() / max_rotation});
  if (std::isfinite(shrink)) delta /= shrink;
  return shrink != 1.0;
}

/// The strut residuals left after the full Newton step δ from the legs in `data` (the pose the
/// Jacobian was taken at), to second order in δ: the first-order part J·δ cancels the residual,
/// what is left is, per leg with unit vector u, length l and joint offset r,
///   s = u·q + (|w|² − (u·w)²) / (2 l),  w = −δp − δθ×r,  q = ½ δθ×(δθ×r)
/// (the leg vector after the step is v + w + q + O(δ³), from exp(−δθ)·r; the length is the
/// second-order Taylor expansion of |v + d|).
StrutVector secondOrderResidual(const HexapodData& data, const StrutVector& delta) {
  const Eigen::Vector3d dp = delta.head<3>();
  const Eigen::Vector3d dtheta = delta.tail<3>();
  StrutVector s;
  for (int i = 0; i < kStruts; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const Eigen::Vector3d c = dtheta.cross(data.world_r_joint[k]);
    const Eigen::Vector3d w = -dp - c;
    const Eigen::Vector3d& u = data.unit_leg[k];
    const double uw = u.dot(w);
    s[i] = 0.5 * u.dot(dtheta.cross(c)) +
           (w.squaredNorm() - uw * uw) * (0.5 * data.inverse_joint_distance[i]);
  }
  return s;
}

/// Corrects the full Newton step δ (from the factorisation `lu` of the scaled Jacobian at the
/// legs in `data`) for its second-order strut residual, with the same factorisation, unless that
/// residual is below what needs polishing (or not finite).
void correctSecondOrder(const detail::Lu6& lu,
                        const HexapodData& data,
                        double inv_length,
                        double tolerance,
                        StrutVector& delta) {
  StrutVector s = secondOrderResidual(data, delta);
  if (s.cwiseAbs().maxCoeff() > detail::kPolishFraction * tolerance && s.allFinite()) {
    detail::substitute6(lu, s);
    s.tail<3>() *= inv_length;
    delta += s;
  }
}

/// The pose x − step·δ: p − step·δp, exp(−step·[δθ]×)·R.
template <typename Pose>
Pose retract(const Pose& at, const StrutVector& delta, double step) {
  return Pose{at.p - step * delta.head<3>(), geometry::so3Exp(-step * delta.tail<3>()) * at.R};
}

/// The Newton step of HexapodFkSolver::solveGeneral's damped iteration (dampedNewton's `solve`)
/// at the legs in `data`, with the state of its linearisations.
struct FkStepSolver {
  FkStepSolver(
      const HexapodModel& m, HexapodData& d, const FkOptions& o, double inv_l, double max_t)
      : model(m), data(d), options(o), inv_length(inv_l), max_translation(max_t) {}

  /// Turns the residual `delta` into the step; returns the pivot ratio of the factorisation.
  double operator()(StrutVector& delta, bool polishing) {
    // The polishing step, after a step that converged, is a chord step: the Jacobian factorised
    // one step before differs from the current one by about the last step's relative size, so it
    // shrinks the residual as much as a new factorisation would.
    if (!polishing || !lu.valid) {
      // The angular columns × 1/L make the pivot test unit-free; δθ is scaled back after.
      lu_ratio = detail::factor6(computeStrutJacobian(model, data), lu, &last_sign, inv_length);
      if (seed_sign == 0) seed_sign = last_sign;
    }
    if (!lu.valid) return lu_ratio;
    // Trust region: a step longer than the options allow is shortened along its direction.
    if (scaledStep(lu, inv_length, max_translation, options.max_step_rotation, delta) || polishing)
      return lu_ratio;
    // A full Newton step leaves a residual of second order in its length. Where that is above
    // what needs polishing, the step is corrected for it with the same factorisation (one
    // substitution, no new evaluation of the legs): the step then lands within O(|δ|³), which on
    // a path of noisy readings saves the polishing step's evaluation.
    correctSecondOrder(lu, data, inv_length, options.tolerance, delta);
    return lu_ratio;
  }

  const HexapodModel& model;
  HexapodData& data;
  const FkOptions& options;
  double inv_length;       ///< 1 / characteristic length
  double max_translation;  ///< trust region of a step's translation (model units)
  detail::Lu6 lu;          ///< the factorisation of the last Newton step
  double lu_ratio = 0.0;   ///< and its pivot ratio
  int seed_sign = 0;       ///< sign of det J at a solve's first linearisation
  int last_sign = 0;       ///< and at its latest
};

/// The number of continuation stages from strut readings `start` to `readings`: stages of at
/// most `stage_length` (model units) in the largest strut change, at most 1000; 1 when the gap
/// is not finite.
int continuationStages(const StrutVector& start, const StrutVector& readings, double stage_length) {
  const double gap = (readings - start).cwiseAbs().maxCoeff();
  constexpr int kMaxStages = 1000;
  return std::isfinite(gap) && gap > stage_length
             ? static_cast<int>(std::min<double>(std::ceil(gap / stage_length), kMaxStages))
             : 1;
}

}  // namespace

std::string_view toString(FkStatus status) {
  switch (status) {
    case FkStatus::kOk:
      return "ok";
    case FkStatus::kNoConvergence:
      return "no_convergence";
    case FkStatus::kSingular:
      return "singular";
    case FkStatus::kInvalidInput:
      return "invalid_input";
    case FkStatus::kOtherBranch:
      return "other_branch";
  }
  return "unknown";
}

bool FkOptions::isValid(std::string* why) const {
  auto fail = [why](const std::string& msg) {
    if (why != nullptr) *why = msg;
    return false;
  };
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    return fail(fmt::format("tolerance must be finite and > 0 (got {})", tolerance));
  if (max_iterations < 1)
    return fail(fmt::format("max_iterations must be >= 1 (got {})", max_iterations));
  if (max_backtracks < 0)
    return fail(fmt::format("max_backtracks must be >= 0 (got {})", max_backtracks));
  if (!(singular_pivot_ratio > 0.0 && singular_pivot_ratio < 1.0))
    return fail(
        fmt::format("singular_pivot_ratio must be in (0, 1) (got {})", singular_pivot_ratio));
  if (!(continuation_step > 0.0))
    return fail(fmt::format("continuation_step must be > 0 (got {})", continuation_step));
  if (!(max_step_translation > 0.0) || !(max_step_rotation > 0.0))
    return fail(fmt::format("max_step_translation and max_step_rotation must be > 0 (got {}, {})",
                            max_step_translation,
                            max_step_rotation));
  return true;
}

FkSummary forwardKinematics(const HexapodModel& model,
                            HexapodData& data,
                            const StrutVector& readings,
                            const PoseRpy& seed,
                            const FkOptions& options) {
  return HexapodFkSolver(model, options)
      .solve(data, readings, seed.position, geometry::rotationFromRpy(seed.rpy), &seed.rpy);
}

FkSummary forwardKinematics(const HexapodModel& model,
                            HexapodData& data,
                            const StrutVector& readings,
                            const Eigen::Vector3d& world_p_seed,
                            const Eigen::Matrix3d& world_R_seed,
                            const Eigen::Vector3d* rpy_near,
                            const FkOptions& options) {
  return HexapodFkSolver(model, options)
      .solve(data, readings, world_p_seed, world_R_seed, rpy_near);
}

HexapodFkSolver::HexapodFkSolver(const HexapodModel& model, const FkOptions& options)
    : model_(model), options_(options) {
  std::string why;
  PKM_CHECK(options.isValid(&why), "invalid FkOptions: {}", why);
  length_ = model.characteristicLength();
  inv_length_ = 1.0 / length_;
  max_translation_ = options.max_step_translation * length_;
}

FkSummary HexapodFkSolver::solve(HexapodData& data,
                                 const StrutVector& readings,
                                 const Eigen::Vector3d& world_p_seed,
                                 const Eigen::Matrix3d& world_R_seed,
                                 const Eigen::Vector3d* rpy_near) const {
  FkSummary summary;
  if (!readings.allFinite() || !world_p_seed.allFinite() || !world_R_seed.allFinite() ||
      (rpy_near != nullptr && !rpy_near->allFinite())) {
    summary.status = FkStatus::kInvalidInput;
    summary.max_residual = INFINITY;
    return summary;
  }
  Pose x{world_p_seed, world_R_seed};
  StrutVector r0;
  const double gap = detail::computeLegsResidual(model_, data, x.p, x.R, readings, r0);
  if (!solveNear(data, readings, r0, gap, x, summary)) {
    x = Pose{world_p_seed, world_R_seed};
    detail::computeLegs(model_, data, x.p, x.R);
    summary = solveGeneral(data, readings, x);
  }
  data.pose.position = x.p;
  if (rpy_near != nullptr) data.pose.rpy = geometry::rpyFromRotation(x.R, *rpy_near);
  return summary;
}

bool HexapodFkSolver::solveNear(HexapodData& data,
                                const StrutVector& readings,
                                const StrutVector& r0,
                                double gap,
                                Pose& x,
                                FkSummary& out) const {
  // The steps of solveGeneral's damped Newton iteration for a seed within one continuation stage
  // whose corrected Newton step is accepted at full length and converges: the same operations in
  // the same order (bit-identical results), without its bookkeeping. Anything else (a seed that
  // is already converged or far, a shortened or rejected step, no convergence) returns false.
  if (!(gap > options_.tolerance && gap <= options_.continuation_step * length_) ||
      options_.max_iterations < 2)
    return false;
  detail::Lu6 lu;
  const double ratio =
      detail::factor6(computeStrutJacobian(model_, data), lu, nullptr, inv_length_);
  StrutVector delta = r0;
  if (!(ratio > options_.singular_pivot_ratio) ||
      scaledStep(lu, inv_length_, max_translation_, options_.max_step_rotation, delta))
    return false;
  correctSecondOrder(lu, data, inv_length_, options_.tolerance, delta);
  if (!delta.allFinite()) return false;
  const Pose x1 = retract<Pose>(x, delta, 1.0);
  StrutVector r1;
  const double max1 = detail::computeLegsResidual(model_, data, x1.p, x1.R, readings, r1);
  if (!(max1 <= options_.tolerance)) return false;
  out.status = FkStatus::kOk;
  out.iterations = 1;
  out.max_residual = max1;
  if (max1 <= detail::kPolishFraction * options_.tolerance) {
    x = x1;
    return true;
  }
  // The polishing step: a chord step with the same factorisation, taken when it reduces |r|.
  StrutVector chord = r1;
  scaledStep(lu, inv_length_, max_translation_, options_.max_step_rotation, chord);
  if (!chord.allFinite()) return false;
  const Pose x2 = retract<Pose>(x1, chord, 1.0);
  StrutVector r2;
  const double max2 = detail::computeLegsResidual(model_, data, x2.p, x2.R, readings, r2);
  const double n2 = r2.squaredNorm();
  if (!(std::isfinite(n2) && n2 < r1.squaredNorm())) return false;  // solveGeneral backtracks
  out.iterations = 2;
  out.max_residual = max2;
  x = x2;
  return true;
}

FkSummary HexapodFkSolver::solveGeneral(HexapodData& data,
                                        const StrutVector& readings,
                                        Pose& x) const {
  const FkOptions& options = options_;
  const double length = length_;
  const double inv_length = inv_length_;
  const double max_translation = max_translation_;
  FkSummary summary;
  StrutVector target = readings;  // the readings the current stage solves for
  bool legs_at_x = false;         // data holds the legs of x (dampedNewton's first evaluation)
  auto evaluate = [&](const Pose& at, StrutVector& r) {
    if (!legs_at_x || &at != &x) detail::computeLegs(model_, data, at.p, at.R);
    legs_at_x = false;
    r = data.readings - target;
    const double n2 = r.squaredNorm();
    return std::isfinite(n2) ? n2 : INFINITY;
  };
  FkStepSolver solve(model_, data, options, inv_length, max_translation);
  // A far seed (a cold start): continuation along the straight line of strut readings from the
  // seed's to the target's, in stages of at most options.continuation_step characteristic
  // lengths, each solved from the previous stage's pose. The answer is then the pose the machine
  // reaches from the seed as its struts move, not whichever root a long Newton step lands near;
  // a determinant sign change between stages means a singularity was crossed (kOtherBranch).
  const StrutVector start = data.readings;
  const int stages = continuationStages(start, readings, options.continuation_step * length);
  FkSummary total;
  FkOptions intermediate = options;
  intermediate.tolerance = std::max(options.tolerance, kStageTolerance * length);
  int previous_sign = 0;
  for (int k = 1; k <= stages; ++k) {
    target =
        k == stages ? readings : StrutVector(start + (readings - start) * (double(k) / stages));
    solve.seed_sign = solve.last_sign = 0;
    legs_at_x =
        true;  // computed by the caller, or left by the last stage (dampedNewton's contract)
    summary = detail::dampedNewton<kStruts>(
        k == stages ? options : intermediate, x, evaluate, solve, retract<Pose>);
    total.iterations += summary.iterations;
    total.backtracks += summary.backtracks;
    if (!summary.ok()) break;
    if (solve.seed_sign == 0) continue;  // converged without a linearisation
    if ((previous_sign != 0 && solve.seed_sign != previous_sign) ||
        solve.last_sign != solve.seed_sign) {
      summary.status = FkStatus::kOtherBranch;
      break;
    }
    previous_sign = solve.last_sign;
  }
  summary.iterations = total.iterations;
  summary.backtracks = total.backtracks;
  if (!summary.ok() && stages > 1) {  // the residual against the readings, not a stage's target
    target = readings;
    StrutVector r;
    evaluate(x, r);
    summary.max_residual = r.cwiseAbs().maxCoeff();
  }
  return summary;
}

}  // namespace pkm::kinematics
