#include "pkm/calibration/hexapod_calibration.hpp"

#include <Eigen/SVD>
#include <cmath>

#include "detail/hexapod_least_squares.hpp"
#include "detail/hexapod_residuals.hpp"
#include "detail/observations.hpp"
#include "pkm/core/error.hpp"

namespace pkm::calibration {
namespace {

using detail::FrameEstimate;
using detail::HexapodUnknownColumns;
using detail::HexapodUnknownValues;
using kinematics::HexapodModel;

/// Appends the indices of the free parameters of `options` to `free_indices` (empty before) and
/// returns the unknowns' layout. Throws pkm::InvalidArgument when no parameter is free or `data`
/// have fewer equations than unknowns.
HexapodUnknownColumns layOutHexapodUnknowns(const HexapodCalibrationData& data,
                                            const HexapodCalibrationOptions& options,
                                            std::vector<int>& free_indices) {
  for (int k = 0; k < kHexapodParameters; ++k)
    if (options.free[static_cast<std::size_t>(k)]) free_indices.push_back(k);
  HexapodUnknownColumns u;
  u.n_free = static_cast<Eigen::Index>(free_indices.size());
  PKM_CHECK(u.n_free > 0, "calibration: no parameter is free");
  u.has_frame = data.measurement_frame.has_value();
  u.n_frame = u.has_frame ? 6 : 0;
  u.has_backlash = options.estimate_backlash;
  u.n_back = u.has_backlash ? kinematics::kStruts : 0;
  const std::size_t unknowns = free_indices.size() + static_cast<std::size_t>(u.n_frame + u.n_back);
  const std::size_t equations = data.equations();
  std::size_t stations = 0;
  for (const ConstrainedMotionData& c : data.constrained) stations += c.stations.size();
  PKM_CHECK(equations >= unknowns,
            "calibration: too few observations: {} poses, {} points and {} gauge stations give {} "
            "equations for {} unknowns",
            data.poses.size(),
            data.points.size(),
            stations,
            equations,
            unknowns);
  return u;
}

/// The names of the unknowns in column order: the free parameters, then the frame correction and
/// the backlash when they are estimated.
std::vector<std::string> hexapodUnknownNames(const std::vector<int>& free_indices,
                                             const HexapodUnknownColumns& u) {
  std::vector<std::string> names;
  for (const int k : free_indices) names.push_back(hexapodParameterName(k));
  if (u.has_frame)
    for (const std::string& n : measurementFrameNames()) names.push_back(n);
  if (u.has_backlash)
    for (const std::string& n : backlashNames()) names.push_back(n);
  return names;
}

/// The unknowns' columns of a stacked Jacobian `J` (42 parameter columns, then the frame's and
/// the backlash's as laid out in `u`): the free parameters', then the frame's and backlash's.
Eigen::MatrixXd selectUnknownColumns(const Eigen::MatrixXd& J,
                                     const std::vector<int>& free_indices,
                                     const HexapodUnknownColumns& u) {
  Eigen::MatrixXd S(J.rows(), u.n_free + u.n_frame + u.n_back);
  for (Eigen::Index c = 0; c < u.n_free; ++c)
    S.col(c) = J.col(free_indices[static_cast<std::size_t>(c)]);
  S.rightCols(u.n_frame + u.n_back) = J.rightCols(u.n_frame + u.n_back);
  return S;
}

/// The structural identifiability of the unknowns at (initial, frame0, backlash0): the Jacobian
/// on the data `initial` predicts for the readings of `data`. (With real residuals, point
/// residuals turn with a rotation of the whole set-up, so the Jacobian of the raw data is not
/// exactly singular along that unobservable rotation.)
Identifiability structuralHexapodIdentifiability(const HexapodModel& initial,
                                                 const HexapodCalibrationData& data,
                                                 const HexapodCalibrationOptions& options,
                                                 const std::vector<int>& free_indices,
                                                 const HexapodUnknownColumns& u,
                                                 const FrameEstimate& frame0,
                                                 const kinematics::StrutVector& backlash0) {
  const std::vector<std::string> names = hexapodUnknownNames(free_indices, u);
  Eigen::MatrixXd J0;
  const HexapodCalibrationData consistent =
      detail::predictedData(initial, data, data.measurement_frame);
  detail::stackHexapodObservations(initial,
                                   consistent,
                                   u.has_frame ? &frame0 : nullptr,
                                   &J0,
                                   nullptr,
                                   nullptr,
                                   u.has_backlash ? &backlash0 : nullptr);
  return analyseIdentifiability(
      selectUnknownColumns(J0, free_indices, u), names, options.identifiability);
}

/// σ²·Σ v_k·v_kᵀ / s_k² over the first `rank` singular triplets (s_k, v_k) of `Js`: the
/// covariance σ²(JᵀJ)⁺ of its n_all columns on their identifiable subspace.
Eigen::MatrixXd unknownCovariance(const Eigen::MatrixXd& Js,
                                  int rank,
                                  double sigma,
                                  Eigen::Index n_all) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Js, Eigen::ComputeThinV);
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(n_all, n_all);
  for (int k = 0; k < rank && k < svd.singularValues().size(); ++k) {
    const double s = svd.singularValues()(k);
    cov += (svd.matrixV().col(k) / (s * s)) * svd.matrixV().col(k).transpose();
  }
  cov *= sigma * sigma;
  return cov;
}

/// Stores the unknowns' covariance `cov` (columns as laid out in `u`) in `out`: the 42 × 42
/// parameter covariance (zero for fixed parameters) and the standard deviations of the
/// parameters, the frame correction and the backlash. Precondition: out.free_indices set.
void storeHexapodCovariance(const Eigen::MatrixXd& cov,
                            const HexapodUnknownColumns& u,
                            HexapodCalibrationSummary& out) {
  out.covariance = Eigen::MatrixXd::Zero(kHexapodParameters, kHexapodParameters);
  for (Eigen::Index a = 0; a < u.n_free; ++a)
    for (Eigen::Index b = 0; b < u.n_free; ++b)
      out.covariance(out.free_indices[static_cast<std::size_t>(a)],
                     out.free_indices[static_cast<std::size_t>(b)]) = cov(a, b);
  out.standard_deviation = out.covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  if (u.has_frame)
    out.frame_standard_deviation = cov.diagonal().segment(u.n_free, 6).cwiseMax(0.0).cwiseSqrt();
  if (u.has_backlash)
    out.backlash_standard_deviation = cov.diagonal().tail<6>().cwiseMax(0.0).cwiseSqrt();
}

/// The fit's results at the solved unknowns `x`: the estimated frame (from frame0) and backlash,
/// the residual statistics after, σ (options.measurement_sigma, else from the residuals and the
/// rank) and the covariance σ²(JᵀJ)⁺ on the identifiable subspace (with prior_weight > 0 the MAP
/// covariance σ²(JᵀJ + w²·I_θ)⁻¹). Precondition: `out` holds the free indices and identifiability.
void evaluateHexapodFit(const HexapodModel& initial,
                        const HexapodCalibrationData& data,
                        const HexapodCalibrationOptions& options,
                        const HexapodUnknownColumns& u,
                        const FrameEstimate& frame0,
                        double prior_weight,
                        const HexapodUnknownValues& x,
                        HexapodCalibrationSummary& out) {
  const HexapodModel estimated = withHexapodParameters(initial, x.theta);
  FrameEstimate frame1 = frame0;
  frame1.delta = x.delta;
  if (u.has_frame) out.measurement_frame = frame1.current();
  if (u.has_backlash) out.backlash = x.backlash;
  out.after = residualStatistics(estimated, data, out.measurement_frame, out.backlash);
  Eigen::MatrixXd J1;
  detail::stackHexapodObservations(estimated,
                                   data,
                                   u.has_frame ? &frame1 : nullptr,
                                   &J1,
                                   nullptr,
                                   nullptr,
                                   u.has_backlash ? &x.backlash : nullptr);
  Eigen::MatrixXd Js = selectUnknownColumns(J1, out.free_indices, u);
  if (prior_weight > 0.0) {  // the prior's rows: the MAP covariance σ²(JᵀJ + w²·I_θ)⁻¹
    Js.conservativeResize(Js.rows() + u.n_free, Eigen::NoChange);
    Js.bottomRows(u.n_free).setZero();
    Js.bottomLeftCorner(u.n_free, u.n_free).diagonal().setConstant(prior_weight);
  }
  const int rank = out.identifiability.rank;
  const double dof = static_cast<double>(out.after.equations - rank);
  out.sigma = options.measurement_sigma > 0.0
                  ? options.measurement_sigma
                  : (dof > 0 ? out.after.rms * std::sqrt(out.after.equations / dof) : 0.0);
  const Eigen::Index n_all = u.n_free + u.n_frame + u.n_back;
  storeHexapodCovariance(unknownCovariance(Js, rank, out.sigma, n_all), u, out);
}

}  // namespace

void HexapodCalibrationOptions::validate() const {
  PKM_CHECK(
      max_iterations >= 1, "calibration: max_iterations must be >= 1, got {}", max_iterations);
  PKM_CHECK(function_tolerance >= 0 && gradient_tolerance >= 0 && parameter_tolerance >= 0,
            "calibration: tolerances must be >= 0");
  PKM_CHECK(loss == RobustLoss::kNone || loss_scale > 0.0,
            "calibration: a robust loss needs loss_scale > 0");
  PKM_CHECK(measurement_sigma >= 0.0 && std::isfinite(measurement_sigma),
            "calibration: measurement_sigma must be finite and >= 0");
  PKM_CHECK(parameter_prior_sigma >= 0.0 && std::isfinite(parameter_prior_sigma),
            "calibration: parameter_prior_sigma must be finite and >= 0");
  PKM_CHECK(prior_uncertainty >= 0.0 && std::isfinite(prior_uncertainty) &&
                (prior_uncertainty == 0.0 || parameter_prior_sigma > 0.0),
            "calibration: prior_uncertainty must be finite, >= 0, and needs parameter_prior_sigma");
  PKM_CHECK(parameter_prior_sigma == 0.0 || measurement_sigma > 0.0,
            "calibration: parameter_prior_sigma needs measurement_sigma > 0 (the prior's weight is "
            "measurement_sigma / parameter_prior_sigma)");
}

HexapodCalibrationSummary calibrateHexapod(const HexapodModel& initial,
                                           const HexapodCalibrationData& data,
                                           const HexapodCalibrationOptions& options) {
  options.validate();
  detail::requireFiniteHexapodData(data);
  HexapodCalibrationSummary out;
  const HexapodUnknownColumns u = layOutHexapodUnknowns(data, options, out.free_indices);

  out.initial = hexapodParameters(initial);
  out.before = residualStatistics(initial, data);
  FrameEstimate frame0;
  if (u.has_frame) frame0.initial = *data.measurement_frame;
  const kinematics::StrutVector backlash0 = kinematics::StrutVector::Zero();
  out.identifiability = structuralHexapodIdentifiability(
      initial, data, options, out.free_indices, u, frame0, backlash0);

  HexapodUnknownValues x{out.initial, Eigen::Matrix<double, 6, 1>::Zero(), backlash0};
  // Tikhonov prior: (σ_r/σ_θ)·(θ_k − θ₀_k) per free parameter (a NullSpacePrior along e_k).
  const double prior_weight = options.parameter_prior_sigma > 0.0
                                  ? options.measurement_sigma / options.parameter_prior_sigma
                                  : 0.0;
  detail::solveHexapodProblem(initial, data, options, u, backlash0, prior_weight, x, out);
  out.parameters = x.theta;
  evaluateHexapodFit(initial, data, options, u, frame0, prior_weight, x, out);
  std::vector<ParameterValues> values;
  for (int k = 0; k < kHexapodParameters; ++k)
    values.push_back({hexapodParameterName(k), out.initial(k), out.parameters(k), true});
  out.large_changes =
      implausibleChanges(values, initial.characteristicLength(), toString(initial.unit));
  return out;
}

}  // namespace pkm::calibration
