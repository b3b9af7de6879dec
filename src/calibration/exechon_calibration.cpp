#include "pkm/calibration/exechon_calibration.hpp"

#include <algorithm>
#include <cmath>

#include "detail/numeric_fit.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/exechon_data.hpp"

namespace pkm::calibration {

/// A fit whose residual RMS exceeds this fraction of the machine size explains nothing.
constexpr double kImplausibleResidualFraction = 0.02;
namespace {

using kinematics::ExechonConfiguration;
using kinematics::ExechonModel;

constexpr double kLengthStep = 1e-3;     // central-difference step of a length unknown, length unit
constexpr double kAngleStep = 1e-6;      // of an angle unknown, rad
constexpr double kUnitTolerance = 1e-6;  // |1 − |u|| of a measured direction

/// world_T_measurement = (exp([δω]×)·R₀, t₀ + δt).
geometry::RigidTransform frameOf(const geometry::RigidTransform& initial,
                                 const Eigen::Ref<const Eigen::VectorXd>& delta) {
  return geometry::perturbedTransform(initial, geometry::Twist(delta));
}

/// The residuals of observation `o` under `model`: world target − predicted (3), then the direction
/// difference times the weight (3, when measured).
bool residuals(const ExechonModel& model,
               const ExechonCalibrationData& data,
               const ExechonObservation& o,
               const ExechonConfiguration& seed,
               const geometry::RigidTransform* frame,
               const ExechonCalibrationOptions& options,
               double* r) {
  kinematics::ExechonData work(model);
  if (!kinematics::toolForwardKinematics(model, work, o.joints, seed, options.fk).ok())
    return false;
  const Eigen::Vector3d predicted = work.world_p_tool + work.world_R_tool * data.target_offset;
  const Eigen::Vector3d world =
      frame != nullptr ? Eigen::Vector3d(frame->linear() * o.point + frame->translation())
                       : o.point;
  Eigen::Map<Eigen::Vector3d> r_point(r);
  r_point = world - predicted;
  if (o.direction) {
    const Eigen::Vector3d u =
        frame != nullptr ? Eigen::Vector3d(frame->linear() * *o.direction) : *o.direction;
    Eigen::Map<Eigen::Vector3d> r_direction(r + 3);
    r_direction = options.direction_weight * (u - work.world_u_tool);
  }
  return true;
}

void requireValid(const ExechonCalibrationData& data) {
  for (std::size_t k = 0; k < data.observations.size(); ++k) {
    const ExechonObservation& o = data.observations[k];
    const std::string where = o.source.empty() ? fmt::format("observation {}", k + 1) : o.source;
    PKM_CHECK(o.joints.readings.allFinite() && std::isfinite(o.joints.c) &&
                  std::isfinite(o.joints.a) && o.point.allFinite(),
              "{}: a non-finite value",
              where);
    if (o.direction)
      PKM_CHECK(o.direction->allFinite() && std::fabs(o.direction->norm() - 1.0) < kUnitTolerance,
                "{}: the measured tool direction is not a unit vector (|u| = {})",
                where,
                o.direction->norm());
  }
  PKM_CHECK(data.target_offset.allFinite(), "calibration: the target offset is not finite");
}

/// FK seeds: the solution of `model` from its home for every observation (nullopt: no FK).
std::vector<std::optional<ExechonConfiguration>> seeds(const ExechonModel& model,
                                                       const ExechonCalibrationData& data,
                                                       const kinematics::FkOptions& fk) {
  std::vector<std::optional<ExechonConfiguration>> out;
  kinematics::ExechonData work(model);
  for (const ExechonObservation& o : data.observations) {
    if (kinematics::toolForwardKinematics(model, work, o.joints, model.home, fk).ok())
      out.emplace_back(kinematics::configurationOf(work));
    else
      out.emplace_back(std::nullopt);
  }
  return out;
}

/// FK seeds of `initial` for every observation of `data` (seeds()). Throws pkm::InvalidArgument
/// when the FK converges for none or fewer than half of them (wrong units or machine).
std::vector<std::optional<ExechonConfiguration>> convergingExechonSeeds(
    const ExechonModel& initial,
    const ExechonCalibrationData& data,
    const kinematics::FkOptions& fk) {
  auto seed = seeds(initial, data, fk);
  const auto converging = static_cast<std::size_t>(
      std::count_if(seed.begin(), seed.end(), [](const auto& s) { return s.has_value(); }));
  PKM_CHECK(
      2 * converging >= data.observations.size() && converging > 0,
      "calibration: the initial model's FK converges for only {} of {} observations; check "
      "the units of the leg and wrist readings (length unit, degrees in files) and the machine",
      converging,
      data.observations.size());
  return seed;
}

/// What an Exechon fit's residuals depend on besides the unknowns and the observations: the
/// initial model and its base reference (world_T_zoppi), the FK seeds, the measurement frame's
/// start (frame0, when has_frame) and the options. Everything it refers to outlives the fit.
struct ExechonFitContext {
  const ExechonModel& initial;
  const geometry::RigidTransform& reference;
  const std::vector<std::optional<ExechonConfiguration>>& seed;
  bool has_frame;
  const geometry::RigidTransform& frame0;
  const ExechonCalibrationOptions& options;
};

/// The unknowns (42 parameters, then the frame correction when c.has_frame), their
/// central-difference steps and the residual blocks of the observations of `d`, evaluated with
/// `c`. `d` and `c` must outlive the problem.
detail::NumericProblem exechonProblem(const ExechonCalibrationData& d, const ExechonFitContext& c) {
  detail::NumericProblem problem;
  for (int k = 0; k < kExechonParameters; ++k) problem.names.push_back(exechonParameterName(k));
  if (c.has_frame)
    for (const std::string& n : measurementFrameNames()) problem.names.push_back(n);
  const Eigen::Index n = problem.unknowns();
  problem.step.resize(n);
  for (Eigen::Index k = 0; k < n; ++k)
    problem.step(k) = (k < kExechonParameters ? exechonParameterIsLength(static_cast<int>(k))
                                              : k < kExechonParameters + 3)
                          ? kLengthStep
                          : kAngleStep;
  for (const ExechonObservation& o : d.observations) problem.rows.push_back(o.direction ? 6 : 3);
  problem.residual = [&d, &c](const Eigen::VectorXd& theta, std::size_t b, double* r) {
    if (!c.seed[b]) return false;
    const ExechonModel m = withExechonParameters(
        c.initial, ExechonParameterVector(theta.head<kExechonParameters>()), c.reference);
    geometry::RigidTransform f = geometry::RigidTransform::Identity();
    if (c.has_frame) f = frameOf(c.frame0, theta.tail(6));
    return residuals(m, d, d.observations[b], *c.seed[b], c.has_frame ? &f : nullptr, c.options, r);
  };
  return problem;
}

/// `data` with every point (and direction) replaced by what c.initial predicts from its FK seed,
/// in the measurement frame c.frame0 when c.has_frame: data the initial model explains exactly,
/// for the structural identifiability. Observations without a seed or FK keep their measurement.
ExechonCalibrationData consistentExechonData(const ExechonCalibrationData& data,
                                             const ExechonFitContext& c) {
  ExechonCalibrationData consistent = data;
  for (std::size_t b = 0; b < consistent.observations.size(); ++b) {
    ExechonObservation& o = consistent.observations[b];
    if (!c.seed[b]) continue;
    kinematics::ExechonData work(c.initial);
    if (!kinematics::toolForwardKinematics(c.initial, work, o.joints, *c.seed[b], c.options.fk)
             .ok())
      continue;
    const Eigen::Vector3d p = work.world_p_tool + work.world_R_tool * data.target_offset;
    o.point = c.has_frame
                  ? Eigen::Vector3d(c.frame0.linear().transpose() * (p - c.frame0.translation()))
                  : p;
    if (o.direction)
      o.direction = c.has_frame ? Eigen::Vector3d(c.frame0.linear().transpose() * work.world_u_tool)
                                : work.world_u_tool;
  }
  return consistent;
}

/// The options.worst_count observations of `data` with the largest target residual (model length
/// unit) under `estimated`, measurements in `frame` (world when empty); largest first.
std::vector<WorstObservation> worstExechonObservations(
    const ExechonModel& estimated,
    const ExechonCalibrationData& data,
    const std::optional<geometry::RigidTransform>& frame,
    const ExechonCalibrationOptions& options) {
  std::vector<WorstObservation> all;
  for (std::size_t b = 0; b < data.observations.size(); ++b) {
    const ExechonObservation& o = data.observations[b];
    const auto p =
        exechonTarget(estimated, o.joints, data.target_offset, estimated.home, options.fk);
    if (!p) continue;
    const Eigen::Vector3d world =
        frame ? Eigen::Vector3d(frame->linear() * o.point + frame->translation()) : o.point;
    all.push_back({b,
                   o.source.empty() ? fmt::format("observation {}", b + 1) : o.source,
                   (world - *p).norm()});
  }
  std::sort(all.begin(), all.end(), [](const WorstObservation& a, const WorstObservation& b) {
    return a.residual > b.residual;
  });
  all.resize(std::min(all.size(), static_cast<std::size_t>(options.worst_count)));
  return all;
}

/// Adds to `out` (estimate and residuals filled) the parameters that moved implausibly far for
/// `initial`'s size and a warning when the residual RMS exceeds kImplausibleResidualFraction of it.
void flagImplausibleExechonFit(const ExechonModel& initial,
                               const ExechonCalibrationOptions& options,
                               ExechonCalibrationSummary& out) {
  const double size = initial.characteristicLength();
  std::vector<ParameterValues> values;
  for (int k = 0; k < kExechonParameters; ++k)
    values.push_back(
        {exechonParameterName(k), out.initial(k), out.parameters(k), exechonParameterIsLength(k)});
  out.large_changes =
      implausibleChanges(values, size, toString(initial.unit), options.max_plausible_change);
  if (out.after.rms > kImplausibleResidualFraction * size)
    out.warnings.push_back(fmt::format(
        "the fit leaves a residual RMS of {:.4g} {}: the model does not explain the data; check "
        "the units, the frame and outliers",
        out.after.rms,
        toString(initial.unit)));
}

}  // namespace

std::size_t ExechonCalibrationData::equations() const {
  std::size_t n = 0;
  for (const ExechonObservation& o : observations) n += o.direction ? 6 : 3;
  return n;
}

void ExechonCalibrationOptions::validate() const {
  PKM_CHECK(
      max_iterations >= 1, "calibration: max_iterations must be >= 1, got {}", max_iterations);
  PKM_CHECK(function_tolerance >= 0 && gradient_tolerance >= 0 && parameter_tolerance >= 0,
            "calibration: tolerances must be >= 0");
  PKM_CHECK(loss == RobustLoss::kNone || (loss_scale > 0.0 && std::isfinite(loss_scale)),
            "calibration: a robust loss needs loss_scale > 0");
  PKM_CHECK(measurement_sigma >= 0.0 && std::isfinite(measurement_sigma),
            "calibration: measurement_sigma must be finite and >= 0");
  PKM_CHECK(direction_weight > 0.0 && std::isfinite(direction_weight),
            "calibration: direction_weight must be finite and > 0");
  PKM_CHECK(worst_count >= 0, "calibration: worst_count must be >= 0");
  PKM_CHECK(max_plausible_change > 0.0 && std::isfinite(max_plausible_change),
            "calibration: max_plausible_change must be finite and > 0");
  std::string why;
  PKM_CHECK(fk.isValid(&why), "calibration: invalid FK options: {}", why);
}

std::optional<Eigen::Vector3d> exechonTarget(const ExechonModel& model,
                                             const kinematics::ExechonJoints& joints,
                                             const Eigen::Vector3d& target_offset,
                                             const ExechonConfiguration& seed,
                                             const kinematics::FkOptions& fk) {
  kinematics::ExechonData work(model);
  if (!kinematics::toolForwardKinematics(model, work, joints, seed, fk).ok()) return std::nullopt;
  return Eigen::Vector3d(work.world_p_tool + work.world_R_tool * target_offset);
}

std::optional<ExechonTargetJacobian> exechonTargetJacobian(const ExechonModel& model,
                                                           const kinematics::ExechonJoints& joints,
                                                           const Eigen::Vector3d& target_offset,
                                                           const ExechonConfiguration& seed,
                                                           const kinematics::FkOptions& fk) {
  const geometry::RigidTransform reference = model.world_T_zoppi;
  const ExechonParameterVector theta = exechonParameters(model, reference);
  ExechonTargetJacobian J;
  for (int k = 0; k < kExechonParameters; ++k) {
    const double h = exechonParameterIsLength(k) ? kLengthStep : kAngleStep;
    ExechonParameterVector plus = theta, minus = theta;
    plus(k) += h;
    minus(k) -= h;
    const auto a = exechonTarget(
        withExechonParameters(model, plus, reference), joints, target_offset, seed, fk);
    const auto b = exechonTarget(
        withExechonParameters(model, minus, reference), joints, target_offset, seed, fk);
    if (!a || !b) return std::nullopt;
    J.col(k) = (*a - *b) / (2.0 * h);
  }
  return J;
}

std::optional<double> exechonTargetUncertainty(const ExechonModel& estimated,
                                               const Eigen::MatrixXd& covariance,
                                               const kinematics::ExechonJoints& joints,
                                               const Eigen::Vector3d& target_offset,
                                               const ExechonConfiguration& seed,
                                               const kinematics::FkOptions& fk) {
  PKM_CHECK(covariance.rows() >= kExechonParameters && covariance.cols() >= kExechonParameters,
            "calibration: the covariance must be at least {0} x {0}",
            kExechonParameters);
  const auto J = exechonTargetJacobian(estimated, joints, target_offset, seed, fk);
  if (!J) return std::nullopt;
  const Eigen::Matrix3d C =
      *J * covariance.topLeftCorner<kExechonParameters, kExechonParameters>() * J->transpose();
  return std::sqrt(std::max(0.0, C.trace()));
}

geometry::RigidTransform initialExechonMeasurementFrame(const ExechonModel& model,
                                                        const ExechonCalibrationData& data,
                                                        const kinematics::FkOptions& fk) {
  std::vector<Eigen::Vector3d> world, measured;
  for (const ExechonObservation& o : data.observations)
    if (const auto p = exechonTarget(model, o.joints, data.target_offset, model.home, fk)) {
      world.push_back(*p);
      measured.push_back(o.point);
    }
  PKM_CHECK(world.size() >= 3,
            "calibration: only {} observations have a converging FK; the measurement frame needs 3",
            world.size());
  return geometry::fitRigidTransform(world, measured);
}

ResidualStatistics exechonResidualStatistics(const ExechonModel& model,
                                             const ExechonCalibrationData& data,
                                             const std::optional<geometry::RigidTransform>& frame,
                                             const kinematics::FkOptions& fk) {
  const std::optional<geometry::RigidTransform>& f = frame ? frame : data.measurement_frame;
  ResidualStatistics s;
  double sum = 0.0;
  for (const ExechonObservation& o : data.observations) {
    const auto p = exechonTarget(model, o.joints, data.target_offset, model.home, fk);
    if (!p) {
      ++s.fk_failures;
      continue;
    }
    const Eigen::Vector3d world =
        f ? Eigen::Vector3d(f->linear() * o.point + f->translation()) : o.point;
    const Eigen::Vector3d r = world - *p;
    sum += r.squaredNorm();
    s.max = std::max(s.max, r.cwiseAbs().maxCoeff());
    s.equations += 3;
  }
  s.rms = s.equations > 0 ? std::sqrt(sum / s.equations) : 0.0;
  return s;
}

ExechonCalibrationSummary calibrateExechon(const ExechonModel& initial,
                                           const ExechonCalibrationData& data,
                                           const ExechonCalibrationOptions& options) {
  options.validate();
  initial.validate();
  requireValid(data);
  const geometry::RigidTransform reference = initial.world_T_zoppi;
  const auto seed = convergingExechonSeeds(initial, data, options.fk);
  const bool has_frame = data.measurement_frame.has_value();
  const geometry::RigidTransform frame0 =
      has_frame ? *data.measurement_frame : geometry::RigidTransform::Identity();
  const ExechonFitContext context{initial, reference, seed, has_frame, frame0, options};

  const detail::NumericProblem problem = exechonProblem(data, context);
  const Eigen::Index n = problem.unknowns();
  // Structural identifiability: the same problem on data the initial model explains exactly.
  const ExechonCalibrationData consistent = consistentExechonData(data, context);
  const detail::NumericProblem structural = exechonProblem(consistent, context);

  detail::NumericOptions no;
  no.free.assign(static_cast<std::size_t>(n), true);
  for (int k = 0; k < kExechonParameters; ++k)
    no.free[static_cast<std::size_t>(k)] = options.free[static_cast<std::size_t>(k)];
  no.max_iterations = options.max_iterations;
  no.function_tolerance = options.function_tolerance;
  no.gradient_tolerance = options.gradient_tolerance;
  no.parameter_tolerance = options.parameter_tolerance;
  no.loss = options.loss;
  no.loss_scale = options.loss_scale;
  no.measurement_sigma = options.measurement_sigma;
  no.identifiability = options.identifiability;

  ExechonCalibrationSummary out;
  out.initial = exechonParameters(initial, reference);
  out.before = exechonResidualStatistics(initial, data, std::nullopt, options.fk);
  Eigen::VectorXd theta0 = Eigen::VectorXd::Zero(n);
  theta0.head<kExechonParameters>() = out.initial;
  const detail::NumericSolution sol = detail::solveNumeric(problem, theta0, no, &structural);
  out.converged = sol.converged;
  out.termination = sol.termination;
  out.iterations = sol.iterations;
  out.initial_cost = sol.initial_cost;
  out.final_cost = sol.final_cost;
  out.seconds = sol.seconds;
  out.parameters = sol.theta.head<kExechonParameters>();
  out.identifiability = sol.identifiability;
  out.free_indices = sol.free_indices;
  out.sigma = sol.sigma;
  out.covariance = sol.covariance;
  out.standard_deviation = sol.standard_deviation.head<kExechonParameters>();
  if (has_frame) {
    out.measurement_frame = frameOf(frame0, sol.theta.tail(6));
    out.frame_standard_deviation = sol.standard_deviation.tail<6>();
  }
  const ExechonModel estimated = withExechonParameters(initial, out.parameters, reference);
  out.after = exechonResidualStatistics(estimated, data, out.measurement_frame, options.fk);
  // Worst observations after the fit (outlier diagnostics).
  out.worst = worstExechonObservations(estimated, data, out.measurement_frame, options);
  flagImplausibleExechonFit(initial, options, out);
  return out;
}

}  // namespace pkm::calibration
