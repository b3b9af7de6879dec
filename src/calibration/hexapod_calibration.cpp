#include "pkm/calibration/hexapod_calibration.hpp"

#include <ceres/ceres.h>

#include <Eigen/SVD>
#include <cmath>
#include <memory>

#include "detail/least_squares.hpp"
#include "detail/observations.hpp"
#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"

namespace pkm::calibration {
namespace {

using detail::FrameEstimate;
using detail::ObservationRef;
using kinematics::HexapodData;
using kinematics::HexapodModel;
using kinematics::PoseRpy;

/// One observation as a Ceres residual block over the parameters (42) and, when the data has a
/// measurement frame, the frame correction (6).
class ObservationCost final : public ceres::CostFunction {
 public:
  ObservationCost(const HexapodModel& model,
                  const HexapodCalibrationData& data,
                  ObservationRef ref,
                  const geometry::RigidTransform* frame,
                  bool backlash)
      : model_(model),
        data_(data),
        ref_(ref),
        has_frame_(frame != nullptr),
        has_backlash_(backlash) {
    if (frame != nullptr) frame_.initial = *frame;
    set_num_residuals(static_cast<int>(ref.rows()));
    mutable_parameter_block_sizes()->push_back(kHexapodParameters);
    if (has_frame_) mutable_parameter_block_sizes()->push_back(6);
    if (has_backlash_) mutable_parameter_block_sizes()->push_back(kinematics::kStruts);
  }
  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const final {
    const HexapodModel m =
        withHexapodParameters(model_, Eigen::Map<const HexapodParameterVector>(parameters[0]));
    FrameEstimate frame = frame_;
    if (has_frame_) frame.delta = Eigen::Map<const Eigen::Matrix<double, 6, 1>>(parameters[1]);
    HexapodData work(m);
    Eigen::MatrixXd Jt, Jf, Jb;
    const bool want = jacobians != nullptr;
    kinematics::StrutVector b = kinematics::StrutVector::Zero();
    const int backlash_block = has_frame_ ? 2 : 1;
    if (has_backlash_) b = Eigen::Map<const kinematics::StrutVector>(parameters[backlash_block]);
    if (!detail::evaluate(m,
                          work,
                          data_,
                          ref_,
                          has_frame_ ? &frame : nullptr,
                          residuals,
                          want ? &Jt : nullptr,
                          want && has_frame_ ? &Jf : nullptr,
                          has_backlash_ ? &b : nullptr,
                          want && has_backlash_ ? &Jb : nullptr))
      return false;
    const Eigen::Index rows = ref_.rows();
    if (want && jacobians[0] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> out(
          jacobians[0], rows, kHexapodParameters);
      out = Jt;
    }
    if (want && has_frame_ && jacobians[1] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> out(
          jacobians[1], rows, 6);
      out = Jf;
    }
    if (want && has_backlash_ && jacobians[backlash_block] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> out(
          jacobians[backlash_block], rows, kinematics::kStruts);
      out = Jb;
    }
    return true;
  }

 private:
  const HexapodModel& model_;
  const HexapodCalibrationData& data_;
  ObservationRef ref_;
  bool has_frame_;
  bool has_backlash_;
  FrameEstimate frame_;
};

/// Holds the estimate at its start along an unidentifiable direction n = (n_θ, n_frame,
/// n_backlash): r = n_θ·(θ − θ₀) + n_frame·δ + n_backlash·(b − b₀), one block per unknown group.
class NullSpacePrior final : public ceres::CostFunction {
 public:
  NullSpacePrior(std::vector<Eigen::VectorXd> n, std::vector<Eigen::VectorXd> start)
      : n_(std::move(n)), start_(std::move(start)) {
    set_num_residuals(1);
    for (const Eigen::VectorXd& v : n_)
      mutable_parameter_block_sizes()->push_back(static_cast<int>(v.size()));
  }
  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const final {
    residuals[0] = 0.0;
    for (std::size_t b = 0; b < n_.size(); ++b) {
      const auto size = n_[b].size();
      const Eigen::Map<const Eigen::VectorXd> x(parameters[b], size);
      residuals[0] += n_[b].dot(x - start_[b]);
      if (jacobians != nullptr && jacobians[b] != nullptr) {
        Eigen::Map<Eigen::VectorXd> out(jacobians[b], size);
        out = n_[b];
      }
    }
    return true;
  }

 private:
  std::vector<Eigen::VectorXd> n_, start_;
};

/// The stacked Jacobian (all observations; 42 + 6·frame + 6·backlash columns) and residuals at
/// (model, frame, backlash).
void stack(const HexapodModel& model,
           const HexapodCalibrationData& data,
           const FrameEstimate* frame,
           Eigen::MatrixXd* J,
           Eigen::VectorXd* r,
           ResidualStatistics* stats,
           const kinematics::StrutVector* backlash = nullptr) {
  const auto refs = detail::observations(data);
  const auto rows = static_cast<Eigen::Index>(data.equations());
  const Eigen::Index n_frame = frame != nullptr ? 6 : 0;
  const Eigen::Index cols = kHexapodParameters + n_frame + (backlash != nullptr ? 6 : 0);
  if (J != nullptr) J->setZero(rows, cols);
  if (r != nullptr) r->setZero(rows);
  HexapodData work(model);
  Eigen::Index row = 0;
  double sum = 0.0;
  for (const ObservationRef& ref : refs) {
    const Eigen::Index n = ref.rows();
    double res[6];
    Eigen::MatrixXd Jt, Jf, Jb;
    const bool ok = detail::evaluate(model,
                                     work,
                                     data,
                                     ref,
                                     frame,
                                     res,
                                     J != nullptr ? &Jt : nullptr,
                                     J != nullptr && frame != nullptr ? &Jf : nullptr,
                                     backlash,
                                     J != nullptr && backlash != nullptr ? &Jb : nullptr);
    if (ok) {
      if (J != nullptr) {
        J->block(row, 0, n, kHexapodParameters) = Jt;
        if (frame != nullptr) J->block(row, kHexapodParameters, n, 6) = Jf;
        if (backlash != nullptr) J->block(row, kHexapodParameters + n_frame, n, 6) = Jb;
      }
      for (Eigen::Index k = 0; k < n; ++k) {
        if (r != nullptr) (*r)(row + k) = res[k];
        if (stats != nullptr) {
          sum += res[k] * res[k];
          stats->max = std::max(stats->max, std::fabs(res[k]));
          ++stats->equations;
        }
      }
    } else if (stats != nullptr) {
      ++stats->fk_failures;
    }
    row += n;
  }
  if (stats != nullptr) stats->rms = stats->equations > 0 ? std::sqrt(sum / stats->equations) : 0.0;
}

void requireFinite(const HexapodCalibrationData& data) {
  for (std::size_t k = 0; k < data.poses.size(); ++k) {
    const PoseObservation& o = data.poses[k];
    PKM_CHECK(o.readings.allFinite() && o.pose.position.allFinite() && o.pose.rpy.allFinite(),
              "calibration: pose observation {} has a non-finite value",
              k + 1);
  }
  for (std::size_t k = 0; k < data.points.size(); ++k) {
    const PointObservation& o = data.points[k];
    PKM_CHECK(o.readings.allFinite() && o.point.allFinite(),
              "calibration: point observation {} has a non-finite value",
              k + 1);
  }
  const auto finite_station = [](const GaugeStation& st) {
    return st.readings.allFinite() && st.command.position.allFinite() &&
           st.command.rpy.allFinite() && std::isfinite(st.gauges[0]) &&
           std::isfinite(st.gauges[1]) && std::isfinite(st.gauges[2]);
  };
  for (std::size_t k = 0; k < data.distances.size(); ++k) {
    const DistanceObservation& o = data.distances[k];
    PKM_CHECK(o.readings.allFinite() && o.from_point.allFinite() && std::isfinite(o.distance) &&
                  o.distance >= 0.0 && (!o.readings_from || o.readings_from->allFinite()),
              "calibration: distance observation {} has a non-finite or negative value",
              k + 1);
  }
  for (std::size_t k = 0; k < data.constrained.size(); ++k) {
    const ConstrainedMotionData& c = data.constrained[k];
    PKM_CHECK(std::fabs(c.table_normal.norm() - 1.0) < 1e-9,
              "calibration: constrained set {}: the table normal is not a unit vector",
              k + 1);
    PKM_CHECK(finite_station(c.reference),
              "calibration: constrained set {}: the reference has a non-finite value",
              k + 1);
    for (std::size_t j = 0; j < c.stations.size(); ++j)
      PKM_CHECK(finite_station(c.stations[j]),
                "calibration: constrained set {}: station {} has a non-finite value",
                k + 1,
                j + 1);
  }
}

ceres::LossFunction* makeLoss(const HexapodCalibrationOptions& options) {
  switch (options.loss) {
    case RobustLoss::kNone:
      return nullptr;
    case RobustLoss::kHuber:
      return new ceres::HuberLoss(options.loss_scale);
    case RobustLoss::kCauchy:
      return new ceres::CauchyLoss(options.loss_scale);
  }
  return nullptr;
}

}  // namespace

std::size_t HexapodCalibrationData::equations() const {
  std::size_t n = 6 * poses.size() + 3 * points.size() + distances.size();
  for (const ConstrainedMotionData& c : constrained) n += 3 * c.stations.size();
  return n;
}

const std::vector<std::string>& measurementFrameNames() {
  static const std::vector<std::string> names{
      "frame.x", "frame.y", "frame.z", "frame.rx", "frame.ry", "frame.rz"};
  return names;
}

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
  PKM_CHECK(parameter_prior_sigma == 0.0 || measurement_sigma > 0.0,
            "calibration: parameter_prior_sigma needs measurement_sigma > 0 (the prior's weight is "
            "measurement_sigma / parameter_prior_sigma)");
}

geometry::RigidTransform initialMeasurementFrame(const HexapodModel& model,
                                                 const HexapodCalibrationData& data) {
  std::vector<Eigen::Vector3d> world, measured;
  HexapodData work(model);
  const auto add = [&](const kinematics::StrutVector& q, const Eigen::Vector3d& p) {
    if (kinematics::forwardKinematics(model, work, q, model.home).ok()) {
      world.push_back(work.world_p_tcp);
      measured.push_back(p);
    }
  };
  for (const PoseObservation& o : data.poses) add(o.readings, o.pose.position);
  for (const PointObservation& o : data.points) add(o.readings, o.point);
  PKM_CHECK(world.size() >= 3,
            "calibration: only {} observations have a converging FK; the measurement frame needs 3",
            world.size());
  return geometry::fitRigidTransform(world, measured);
}

Eigen::MatrixXd identificationJacobian(const HexapodModel& model,
                                       const HexapodCalibrationData& data) {
  Eigen::MatrixXd J;
  FrameEstimate frame;
  if (data.measurement_frame) frame.initial = *data.measurement_frame;
  stack(model, data, data.measurement_frame ? &frame : nullptr, &J, nullptr, nullptr);
  return J;
}

ResidualStatistics residualStatistics(const HexapodModel& model,
                                      const HexapodCalibrationData& data,
                                      const std::optional<geometry::RigidTransform>& frame,
                                      const std::optional<kinematics::StrutVector>& backlash) {
  ResidualStatistics s;
  const std::optional<geometry::RigidTransform>& f = frame ? frame : data.measurement_frame;
  FrameEstimate estimate;
  if (f) estimate.initial = *f;
  stack(
      model, data, f ? &estimate : nullptr, nullptr, nullptr, &s, backlash ? &*backlash : nullptr);
  return s;
}

const std::vector<std::string>& backlashNames() {
  static const std::vector<std::string> names{
      "backlash0", "backlash1", "backlash2", "backlash3", "backlash4", "backlash5"};
  return names;
}

std::vector<kinematics::StrutVector> approachFromSequence(
    const std::vector<kinematics::StrutVector>& readings, double first) {
  std::vector<kinematics::StrutVector> out;
  kinematics::StrutVector d = kinematics::StrutVector::Constant(first);
  for (std::size_t k = 0; k < readings.size(); ++k) {
    if (k > 0)
      for (int i = 0; i < kinematics::kStruts; ++i) {
        const double change = readings[k](i) - readings[k - 1](i);
        if (change != 0.0) d(i) = change > 0.0 ? 1.0 : -1.0;
      }
    out.push_back(d);
  }
  return out;
}

std::vector<double> observationResidualNorms(
    const HexapodModel& model,
    const HexapodCalibrationData& data,
    const std::optional<geometry::RigidTransform>& frame,
    const std::optional<kinematics::StrutVector>& backlash) {
  const std::optional<geometry::RigidTransform>& f = frame ? frame : data.measurement_frame;
  FrameEstimate estimate;
  if (f) estimate.initial = *f;
  HexapodData work(model);
  std::vector<double> out;
  for (const ObservationRef& ref : detail::observations(data)) {
    double r[6];
    const bool ok = detail::evaluate(model,
                                     work,
                                     data,
                                     ref,
                                     f ? &estimate : nullptr,
                                     r,
                                     nullptr,
                                     nullptr,
                                     backlash ? &*backlash : nullptr,
                                     nullptr);
    out.push_back(ok ? Eigen::Map<const Eigen::VectorXd>(r, ref.rows()).norm() : -1.0);
  }
  return out;
}

HexapodCalibrationSummary calibrateHexapod(const HexapodModel& initial,
                                           const HexapodCalibrationData& data,
                                           const HexapodCalibrationOptions& options) {
  options.validate();
  requireFinite(data);
  HexapodCalibrationSummary out;
  for (int k = 0; k < kHexapodParameters; ++k)
    if (options.free[static_cast<std::size_t>(k)]) out.free_indices.push_back(k);
  const auto n_free = static_cast<Eigen::Index>(out.free_indices.size());
  PKM_CHECK(n_free > 0, "calibration: no parameter is free");
  const bool has_frame = data.measurement_frame.has_value();
  const Eigen::Index n_frame = has_frame ? 6 : 0;
  const bool has_backlash = options.estimate_backlash;
  const Eigen::Index n_back = has_backlash ? kinematics::kStruts : 0;
  const std::size_t unknowns = out.free_indices.size() + static_cast<std::size_t>(n_frame + n_back);
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

  out.initial = hexapodParameters(initial);
  out.before = residualStatistics(initial, data);
  FrameEstimate frame0;
  if (has_frame) frame0.initial = *data.measurement_frame;
  // Columns: the free parameters, then the frame correction.
  std::vector<std::string> names;
  for (const int k : out.free_indices) names.push_back(hexapodParameterName(k));
  if (has_frame)
    for (const std::string& n : measurementFrameNames()) names.push_back(n);
  if (has_backlash)
    for (const std::string& n : backlashNames()) names.push_back(n);
  const auto select = [&](const Eigen::MatrixXd& J) {
    Eigen::MatrixXd S(J.rows(), n_free + n_frame + n_back);
    for (Eigen::Index c = 0; c < n_free; ++c)
      S.col(c) = J.col(out.free_indices[static_cast<std::size_t>(c)]);
    S.rightCols(n_frame + n_back) = J.rightCols(n_frame + n_back);
    return S;
  };
  const kinematics::StrutVector backlash0 = kinematics::StrutVector::Zero();
  // Structural identifiability: the Jacobian on data the initial model explains exactly. (With
  // real residuals, point residuals turn with a rotation of the whole set-up, so the Jacobian of
  // the raw data is not exactly singular along that unobservable rotation.)
  Eigen::MatrixXd J0;
  const HexapodCalibrationData consistent =
      detail::predictedData(initial, data, data.measurement_frame);
  stack(initial,
        consistent,
        has_frame ? &frame0 : nullptr,
        &J0,
        nullptr,
        nullptr,
        has_backlash ? &backlash0 : nullptr);
  out.identifiability = analyseIdentifiability(select(J0), names, options.identifiability);

  HexapodParameterVector theta = out.initial;
  Eigen::Matrix<double, 6, 1> delta = Eigen::Matrix<double, 6, 1>::Zero();
  kinematics::StrutVector backlash = backlash0;
  std::vector<double*> blocks{theta.data()};
  if (has_frame) blocks.push_back(delta.data());
  if (has_backlash) blocks.push_back(backlash.data());
  ceres::Problem problem;
  const geometry::RigidTransform* frame_ptr = has_frame ? &*data.measurement_frame : nullptr;
  for (const ObservationRef& ref : detail::observations(data))
    problem.AddResidualBlock(new ObservationCost(initial, data, ref, frame_ptr, has_backlash),
                             makeLoss(options),
                             blocks);
  for (Eigen::Index k = 0; k < out.identifiability.null_space.cols(); ++k) {
    const Eigen::VectorXd col = out.identifiability.null_space.col(k);
    Eigen::VectorXd n = Eigen::VectorXd::Zero(kHexapodParameters);
    for (Eigen::Index c = 0; c < n_free; ++c)
      n(out.free_indices[static_cast<std::size_t>(c)]) = col(c);
    std::vector<Eigen::VectorXd> ns{n}, starts{Eigen::VectorXd(out.initial)};
    if (has_frame) {
      ns.emplace_back(col.segment(n_free, 6));
      starts.emplace_back(Eigen::VectorXd::Zero(6));
    }
    if (has_backlash) {
      ns.emplace_back(col.tail(6));
      starts.emplace_back(Eigen::VectorXd(backlash0));
    }
    problem.AddResidualBlock(new NullSpacePrior(ns, starts), nullptr, blocks);
  }
  // Tikhonov prior: (σ_r/σ_θ)·(θ_k − θ₀_k) per free parameter (a NullSpacePrior along e_k).
  const double prior_weight = options.parameter_prior_sigma > 0.0
                                  ? options.measurement_sigma / options.parameter_prior_sigma
                                  : 0.0;
  if (prior_weight > 0.0)
    for (const int k : out.free_indices) {
      std::vector<Eigen::VectorXd> ns{prior_weight * Eigen::VectorXd::Unit(kHexapodParameters, k)};
      std::vector<Eigen::VectorXd> starts{Eigen::VectorXd(out.initial)};
      if (has_frame) {
        ns.emplace_back(Eigen::VectorXd::Zero(6));
        starts.emplace_back(Eigen::VectorXd::Zero(6));
      }
      if (has_backlash) {
        ns.emplace_back(Eigen::VectorXd::Zero(6));
        starts.emplace_back(Eigen::VectorXd(backlash0));
      }
      problem.AddResidualBlock(new NullSpacePrior(ns, starts), nullptr, blocks);
    }
  detail::holdFixedParameters(problem, theta.data(), kHexapodParameters, options.free);
  detail::solveLeastSquares(problem,
                            {options.max_iterations,
                             options.function_tolerance,
                             options.gradient_tolerance,
                             options.parameter_tolerance})
      .copyTo(out);
  out.parameters = theta;

  const HexapodModel estimated = withHexapodParameters(initial, theta);
  FrameEstimate frame1 = frame0;
  frame1.delta = delta;
  if (has_frame) out.measurement_frame = frame1.current();
  if (has_backlash) out.backlash = backlash;
  out.after = residualStatistics(estimated, data, out.measurement_frame, out.backlash);
  // Covariance σ²(JᵀJ)⁺ on the identifiable subspace of the unknowns.
  Eigen::MatrixXd J1;
  stack(estimated,
        data,
        has_frame ? &frame1 : nullptr,
        &J1,
        nullptr,
        nullptr,
        has_backlash ? &backlash : nullptr);
  Eigen::MatrixXd Js = select(J1);
  if (prior_weight > 0.0) {  // the prior's rows: the MAP covariance σ²(JᵀJ + w²·I_θ)⁻¹
    Js.conservativeResize(Js.rows() + n_free, Eigen::NoChange);
    Js.bottomRows(n_free).setZero();
    Js.bottomLeftCorner(n_free, n_free).diagonal().setConstant(prior_weight);
  }
  const int rank = out.identifiability.rank;
  const double dof = static_cast<double>(out.after.equations - rank);
  out.sigma = options.measurement_sigma > 0.0
                  ? options.measurement_sigma
                  : (dof > 0 ? out.after.rms * std::sqrt(out.after.equations / dof) : 0.0);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(Js, Eigen::ComputeThinV);
  const Eigen::Index n_all = n_free + n_frame + n_back;
  Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(n_all, n_all);
  for (int k = 0; k < rank && k < svd.singularValues().size(); ++k) {
    const double s = svd.singularValues()(k);
    cov += (svd.matrixV().col(k) / (s * s)) * svd.matrixV().col(k).transpose();
  }
  cov *= out.sigma * out.sigma;
  out.covariance = Eigen::MatrixXd::Zero(kHexapodParameters, kHexapodParameters);
  for (Eigen::Index a = 0; a < n_free; ++a)
    for (Eigen::Index b = 0; b < n_free; ++b)
      out.covariance(out.free_indices[static_cast<std::size_t>(a)],
                     out.free_indices[static_cast<std::size_t>(b)]) = cov(a, b);
  out.standard_deviation = out.covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  if (has_frame)
    out.frame_standard_deviation = cov.diagonal().segment(n_free, 6).cwiseMax(0.0).cwiseSqrt();
  if (has_backlash)
    out.backlash_standard_deviation = cov.diagonal().tail<6>().cwiseMax(0.0).cwiseSqrt();
  std::vector<ParameterValues> values;
  for (int k = 0; k < kHexapodParameters; ++k)
    values.push_back({hexapodParameterName(k), out.initial(k), out.parameters(k), true});
  out.large_changes =
      implausibleChanges(values, initial.characteristicLength(), toString(initial.unit));
  return out;
}

}  // namespace pkm::calibration
