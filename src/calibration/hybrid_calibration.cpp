#include "pkm/calibration/hybrid_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "detail/numeric_fit.hpp"
#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/geometry/so3.hpp"

namespace pkm::calibration {
namespace {

constexpr double kAngleStep = 1e-7;   // rad, central-difference step of a squareness
constexpr double kLengthStep = 1e-3;  // length unit, of a frame translation
constexpr double kFrameAngleStep = 1e-6;

kinematics::HybridSquareness fromVector(const Eigen::Ref<const Eigen::VectorXd>& v) {
  kinematics::HybridSquareness s;
  s.sz_x2 = v(0);
  s.sx_p = v(1);
  s.sy_p = v(2);
  s.sz_p = v(3);
  return s;
}

geometry::RigidTransform frameOf(const geometry::RigidTransform& initial,
                                 const Eigen::Ref<const Eigen::VectorXd>& delta) {
  return geometry::perturbedTransform(initial, geometry::Twist(delta));
}

/// The tripod's error motion at each observation's PKM command, evaluated once: it does not
/// depend on the fitted unknowns, and each evaluation solves the tripod's kinematics. An empty
/// tripod gives identity motions.
class MotionCache {
 public:
  MotionCache(const HybridCalibrationData& d, const TripodMotion& tripod) : has_(bool(tripod)) {
    if (!has_) return;
    motions_.reserve(d.observations.size());
    for (const HybridObservation& o : d.observations) motions_.push_back(tripod(o.command.pkm));
  }
  /// The motion at observation b; nullopt when the tripod cannot reach it.
  [[nodiscard]] std::optional<geometry::RigidTransform> at(std::size_t b) const {
    return has_ ? motions_[b] : geometry::RigidTransform::Identity();
  }

 private:
  bool has_;
  std::vector<std::optional<geometry::RigidTransform>> motions_;
};

/// The point residuals of hybrid observations (3 each, model length unit) under the unknowns
/// θ = (szX2, sxP, syP, szP in rad; then the frame correction when has_frame): the measured
/// point (through frameOf(frame0, θ_frame) when has_frame) − the target `model` predicts, with
/// the tripod's motion taken from `motion` (same observation order as every data set evaluated).
struct HybridFitResiduals {
  const kinematics::HybridMachineModel& model;
  const kinematics::GeometricErrors& known;
  const MotionCache& motion;
  bool has_frame;
  const geometry::RigidTransform& frame0;

  /// The target of observation b of `d` under `squareness`; nullopt without the tripod's motion.
  [[nodiscard]] std::optional<Eigen::Vector3d> target(
      const HybridCalibrationData& d,
      const kinematics::HybridSquareness& squareness,
      std::size_t b) const {
    const auto E = motion.at(b);
    if (!E) return std::nullopt;
    const kinematics::HybridCommand& c = d.observations[b].command;
    kinematics::HybridErrorValues values = kinematics::evaluateHybridErrors(known, c);
    values.squareness = squareness;
    const geometry::RigidTransform T = kinematics::hybridActualPose(model, values, c) * *E;
    return Eigen::Vector3d(T * d.target_offset);
  }

  /// The residuals of observation b of `d` at θ into r (3 values); false when the tripod's
  /// motion cannot be evaluated.
  bool operator()(const HybridCalibrationData& d,
                  const Eigen::VectorXd& theta,
                  std::size_t b,
                  double* r) const {
    const HybridObservation& o = d.observations[b];
    const auto p = target(d, fromVector(theta.head<4>()), b);
    if (!p) return false;
    Eigen::Vector3d measured = o.point;
    if (has_frame) {
      const geometry::RigidTransform f = frameOf(frame0, theta.tail(6));
      measured = f.linear() * o.point + f.translation();
    }
    Eigen::Map<Eigen::Vector3d> out(r);
    out = measured - *p;
    return true;
  }
};

/// Throws pkm::InvalidArgument naming the first observation of `data` with a non-finite value, or
/// when the target offset is not finite.
void requireFiniteHybridData(const HybridCalibrationData& data) {
  for (std::size_t k = 0; k < data.observations.size(); ++k) {
    const HybridObservation& o = data.observations[k];
    PKM_CHECK(std::isfinite(o.command.x2) && std::isfinite(o.command.y2) &&
                  o.command.pkm.allFinite() && o.point.allFinite(),
              "{}: a non-finite value",
              o.source.empty() ? fmt::format("observation {}", k + 1) : o.source);
  }
  PKM_CHECK(data.target_offset.allFinite(), "calibration: the target offset is not finite");
}

/// The unknowns (4 squareness angles, then the frame correction when e.has_frame), their
/// central-difference steps and one 3-row residual block per observation of `d`, evaluated by
/// `e`. `d` and `e` must outlive the problem.
detail::NumericProblem hybridProblem(const HybridCalibrationData& d, const HybridFitResiduals& e) {
  detail::NumericProblem problem;
  problem.names = hybridSquarenessNames();
  if (e.has_frame)
    for (const std::string& n : measurementFrameNames()) problem.names.push_back(n);
  const Eigen::Index n = problem.unknowns();
  problem.step.resize(n);
  problem.step.head<4>().setConstant(kAngleStep);
  if (e.has_frame) {
    problem.step.segment<3>(4).setConstant(kLengthStep);
    problem.step.tail<3>().setConstant(kFrameAngleStep);
  }
  problem.rows.assign(d.observations.size(), 3);
  problem.residual = [&d, &e](const Eigen::VectorXd& theta, std::size_t b, double* r) {
    return e(d, theta, b, r);
  };
  return problem;
}

/// `data` with every point replaced by the target the zero-squareness model predicts (in the
/// measurement frame e.frame0): data it explains exactly, for the structural identifiability.
/// Observations whose tripod motion fails keep their measurement.
HybridCalibrationData consistentHybridData(const HybridCalibrationData& data,
                                           const HybridFitResiduals& e) {
  HybridCalibrationData consistent = data;
  for (std::size_t b = 0; b < consistent.observations.size(); ++b)
    if (const auto p = e.target(data, {}, b))
      consistent.observations[b].point =
          e.frame0.linear().transpose() * (*p - e.frame0.translation());
  return consistent;
}

/// The residual statistics (model length unit) of `data` at θ; observations that cannot be
/// evaluated count as FK failures.
ResidualStatistics hybridFitStatistics(const HybridFitResiduals& evaluate,
                                       const HybridCalibrationData& data,
                                       const Eigen::VectorXd& theta) {
  ResidualStatistics s;
  double sum = 0.0;
  for (std::size_t b = 0; b < data.observations.size(); ++b) {
    double r[3];
    if (!evaluate(data, theta, b, r)) {
      ++s.fk_failures;
      continue;
    }
    for (const double v : r) {
      sum += v * v;
      s.max = std::max(s.max, std::fabs(v));
    }
    s.equations += 3;
  }
  s.rms = s.equations > 0 ? std::sqrt(sum / s.equations) : 0.0;
  return s;
}

/// The `worst_count` observations of `data` with the largest residual norm at θ (model length
/// unit), largest first.
std::vector<WorstObservation> worstHybridObservations(const HybridFitResiduals& evaluate,
                                                      const HybridCalibrationData& data,
                                                      const Eigen::VectorXd& theta,
                                                      int worst_count) {
  std::vector<WorstObservation> all;
  for (std::size_t b = 0; b < data.observations.size(); ++b) {
    double r[3];
    if (!evaluate(data, theta, b, r)) continue;
    const std::string& src = data.observations[b].source;
    all.push_back({b,
                   src.empty() ? fmt::format("observation {}", b + 1) : src,
                   Eigen::Map<const Eigen::Vector3d>(r).norm()});
  }
  std::sort(all.begin(), all.end(), [](const WorstObservation& a, const WorstObservation& b) {
    return a.residual > b.residual;
  });
  all.resize(std::min(all.size(), static_cast<std::size_t>(worst_count)));
  return all;
}

}  // namespace

const std::vector<std::string>& hybridSquarenessNames() {
  static const std::vector<std::string> names{"szX2", "sxP", "syP", "szP"};
  return names;
}

void HybridCalibrationOptions::validate() const {
  PKM_CHECK(
      max_iterations >= 1, "calibration: max_iterations must be >= 1, got {}", max_iterations);
  PKM_CHECK(function_tolerance >= 0 && gradient_tolerance >= 0 && parameter_tolerance >= 0,
            "calibration: tolerances must be >= 0");
  PKM_CHECK(loss == RobustLoss::kNone || (loss_scale > 0.0 && std::isfinite(loss_scale)),
            "calibration: a robust loss needs loss_scale > 0");
  PKM_CHECK(measurement_sigma >= 0.0 && std::isfinite(measurement_sigma),
            "calibration: measurement_sigma must be finite and >= 0");
  PKM_CHECK(worst_count >= 0, "calibration: worst_count must be >= 0");
}

std::optional<Eigen::Vector3d> hybridTarget(const kinematics::HybridMachineModel& model,
                                            const kinematics::GeometricErrors& known,
                                            const kinematics::HybridSquareness& squareness,
                                            const kinematics::HybridCommand& command,
                                            const Eigen::Vector3d& target_offset,
                                            const TripodMotion& tripod) {
  kinematics::HybridErrorValues values = kinematics::evaluateHybridErrors(known, command);
  values.squareness = squareness;
  geometry::RigidTransform T = kinematics::hybridActualPose(model, values, command);
  if (tripod) {
    const auto E = tripod(command.pkm);
    if (!E) return std::nullopt;
    T = T * *E;
  }
  return Eigen::Vector3d(T * target_offset);
}

HybridCalibrationSummary calibrateHybridSquareness(const kinematics::HybridMachineModel& model,
                                                   const kinematics::GeometricErrors& known,
                                                   const HybridCalibrationData& data,
                                                   const HybridCalibrationOptions& options,
                                                   const TripodMotion& tripod) {
  options.validate();
  model.validate();
  known.validate();
  requireFiniteHybridData(data);
  const bool has_frame = data.measurement_frame.has_value();
  const geometry::RigidTransform frame0 =
      has_frame ? *data.measurement_frame : geometry::RigidTransform::Identity();
  const MotionCache motion(data, tripod);
  const HybridFitResiduals evaluate{model, known, motion, has_frame, frame0};

  const detail::NumericProblem problem = hybridProblem(data, evaluate);
  const Eigen::Index n = problem.unknowns();
  // Structural identifiability on data the zero-squareness model explains exactly.
  const HybridCalibrationData consistent = consistentHybridData(data, evaluate);
  const detail::NumericProblem structural = hybridProblem(consistent, evaluate);

  detail::NumericOptions no;
  no.free.assign(static_cast<std::size_t>(n), true);
  for (std::size_t k = 0; k < 4; ++k) no.free[k] = options.free[k];
  no.max_iterations = options.max_iterations;
  no.function_tolerance = options.function_tolerance;
  no.gradient_tolerance = options.gradient_tolerance;
  no.parameter_tolerance = options.parameter_tolerance;
  no.loss = options.loss;
  no.loss_scale = options.loss_scale;
  no.measurement_sigma = options.measurement_sigma;
  no.identifiability = options.identifiability;

  const Eigen::VectorXd theta0 = Eigen::VectorXd::Zero(n);
  HybridCalibrationSummary out;
  out.before = hybridFitStatistics(evaluate, data, theta0);
  const detail::NumericSolution sol = detail::solveNumeric(problem, theta0, no, &structural);
  out.converged = sol.converged;
  out.termination = sol.termination;
  out.iterations = sol.iterations;
  out.initial_cost = sol.initial_cost;
  out.final_cost = sol.final_cost;
  out.seconds = sol.seconds;
  out.squareness = fromVector(sol.theta.head<4>());
  out.standard_deviation = sol.standard_deviation.head<4>();
  out.identifiability = sol.identifiability;
  if (has_frame) out.measurement_frame = frameOf(frame0, sol.theta.tail(6));
  out.after = hybridFitStatistics(evaluate, data, sol.theta);
  out.worst = worstHybridObservations(evaluate, data, sol.theta, options.worst_count);
  return out;
}

}  // namespace pkm::calibration
