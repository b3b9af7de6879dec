#include "pkm/calibration/hexapod_calibration.hpp"

#include <ceres/ceres.h>

#include <Eigen/SVD>
#include <chrono>
#include <cmath>
#include <memory>

#include "pkm/core/error.hpp"

namespace pkm::calibration {
namespace {

using kinematics::HexapodData;
using kinematics::HexapodModel;
using kinematics::PoseRpy;
using RowJacobian = Eigen::Matrix<double, Eigen::Dynamic, kHexapodParameters, Eigen::RowMajor>;

/// The FK seed of a point observation: the measured point with the home orientation.
PoseRpy pointSeed(const HexapodModel& model, const PointObservation& obs) {
  PoseRpy seed = model.home;
  seed.position = obs.point;
  return seed;
}

/// IK residuals of one full-pose observation.
class PoseCost final : public ceres::SizedCostFunction<6, kHexapodParameters> {
 public:
  PoseCost(const HexapodModel& model, const PoseObservation& obs) : model_(model), obs_(obs) {}
  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const final {
    const HexapodModel m = withParameters(parameters[0]);
    HexapodData data(m);
    PoseParameterJacobian J;
    const auto r = poseResiduals(m, data, obs_, jacobians != nullptr ? &J : nullptr);
    Eigen::Map<Eigen::Matrix<double, 6, 1>> r_out(residuals);
    r_out = r;
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, 6, kHexapodParameters, Eigen::RowMajor>> J_out(jacobians[0]);
      J_out = J;
    }
    return true;
  }

 private:
  HexapodModel withParameters(const double* p) const {
    return withHexapodParameters(model_, Eigen::Map<const HexapodParameterVector>(p));
  }
  const HexapodModel& model_;
  const PoseObservation& obs_;
};

/// FK residuals of one point observation; a failed FK makes Ceres reject the step.
class PointCost final : public ceres::SizedCostFunction<3, kHexapodParameters> {
 public:
  PointCost(const HexapodModel& model, const PointObservation& obs) : model_(model), obs_(obs) {}
  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const final {
    const HexapodModel m =
        withHexapodParameters(model_, Eigen::Map<const HexapodParameterVector>(parameters[0]));
    HexapodData data(m);
    PointParameterJacobian J;
    const auto r =
        pointResiduals(m, data, obs_, pointSeed(model_, obs_), jacobians != nullptr ? &J : nullptr);
    if (!r) return false;
    Eigen::Map<Eigen::Vector3d> r_out(residuals);
    r_out = *r;
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, 3, kHexapodParameters, Eigen::RowMajor>> J_out(jacobians[0]);
      J_out = J;
    }
    return true;
  }

 private:
  const HexapodModel& model_;
  const PointObservation& obs_;
};

/// Plane-contact residuals of one gauge station.
class GaugeCost final : public ceres::SizedCostFunction<3, kHexapodParameters> {
 public:
  GaugeCost(const HexapodModel& model, const ConstrainedMotionData& set, std::size_t k)
      : model_(model), set_(set), k_(k) {}
  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const final {
    const HexapodModel m =
        withHexapodParameters(model_, Eigen::Map<const HexapodParameterVector>(parameters[0]));
    HexapodData data(m);
    GaugeParameterJacobian J;
    const auto r = constrainedResiduals(m, data, set_, k_, jacobians != nullptr ? &J : nullptr);
    if (!r) return false;
    Eigen::Map<Eigen::Vector3d> r_out(residuals);
    r_out = *r;
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, 3, kHexapodParameters, Eigen::RowMajor>> J_out(jacobians[0]);
      J_out = J;
    }
    return true;
  }

 private:
  const HexapodModel& model_;
  const ConstrainedMotionData& set_;
  std::size_t k_;
};

/// Holds the parameters at θ₀ along an unidentifiable direction n: r = n·(θ − θ₀).
class NullSpacePrior final : public ceres::SizedCostFunction<1, kHexapodParameters> {
 public:
  NullSpacePrior(HexapodParameterVector n, HexapodParameterVector theta0)
      : n_(std::move(n)), theta0_(std::move(theta0)) {}
  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const final {
    const Eigen::Map<const HexapodParameterVector> theta(parameters[0]);
    residuals[0] = n_.dot(theta - theta0_);
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      Eigen::Map<HexapodParameterVector> J_out(jacobians[0]);
      J_out = n_;
    }
    return true;
  }

 private:
  HexapodParameterVector n_, theta0_;
};

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
  std::size_t n = 6 * poses.size() + 3 * points.size();
  for (const ConstrainedMotionData& c : constrained) n += 3 * c.stations.size();
  return n;
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
}

Eigen::MatrixXd identificationJacobian(const HexapodModel& model,
                                       const HexapodCalibrationData& data) {
  const auto rows = static_cast<Eigen::Index>(data.equations());
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(rows, kHexapodParameters);
  HexapodData work(model);
  Eigen::Index row = 0;
  for (const PoseObservation& o : data.poses) {
    PoseParameterJacobian Jp;
    (void)poseResiduals(model, work, o, &Jp);
    J.middleRows<6>(row) = Jp;
    row += 6;
  }
  for (const PointObservation& o : data.points) {
    PointParameterJacobian Jp;
    if (pointResiduals(model, work, o, pointSeed(model, o), &Jp)) J.middleRows<3>(row) = Jp;
    row += 3;
  }
  for (const ConstrainedMotionData& c : data.constrained)
    for (std::size_t k = 0; k < c.stations.size(); ++k) {
      GaugeParameterJacobian Jg;
      if (constrainedResiduals(model, work, c, k, &Jg)) J.middleRows<3>(row) = Jg;
      row += 3;
    }
  return J;
}

ResidualStatistics residualStatistics(const HexapodModel& model,
                                      const HexapodCalibrationData& data) {
  ResidualStatistics s;
  HexapodData work(model);
  double sum = 0.0;
  const auto add = [&](double r) {
    sum += r * r;
    s.max = std::max(s.max, std::fabs(r));
    ++s.equations;
  };
  for (const PoseObservation& o : data.poses)
    for (const double r : poseResiduals(model, work, o)) add(r);
  for (const PointObservation& o : data.points) {
    const auto r = pointResiduals(model, work, o, pointSeed(model, o));
    if (!r) {
      ++s.fk_failures;
      continue;
    }
    for (const double v : *r) add(v);
  }
  for (const ConstrainedMotionData& c : data.constrained)
    for (std::size_t k = 0; k < c.stations.size(); ++k) {
      const auto r = constrainedResiduals(model, work, c, k);
      if (!r) {
        ++s.fk_failures;
        continue;
      }
      for (const double v : *r) add(v);
    }
  s.rms = s.equations > 0 ? std::sqrt(sum / s.equations) : 0.0;
  return s;
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
  const std::size_t equations = data.equations();
  std::size_t stations = 0;
  for (const ConstrainedMotionData& c : data.constrained) stations += c.stations.size();
  PKM_CHECK(equations >= out.free_indices.size(),
            "calibration: too few observations: {} poses, {} points and {} gauge stations give {} "
            "equations for {} free parameters",
            data.poses.size(),
            data.points.size(),
            stations,
            equations,
            out.free_indices.size());

  out.initial = hexapodParameters(initial);
  out.before = residualStatistics(initial, data);
  std::vector<std::string> names;
  for (const int k : out.free_indices) names.push_back(hexapodParameterName(k));
  const Eigen::MatrixXd J0 = identificationJacobian(initial, data);
  Eigen::MatrixXd J0_free(J0.rows(), n_free);
  for (Eigen::Index c = 0; c < n_free; ++c)
    J0_free.col(c) = J0.col(out.free_indices[static_cast<std::size_t>(c)]);
  out.identifiability = analyseIdentifiability(J0_free, names, options.identifiability);

  HexapodParameterVector theta = out.initial;
  ceres::Problem problem;
  for (const PoseObservation& o : data.poses)
    problem.AddResidualBlock(new PoseCost(initial, o), makeLoss(options), theta.data());
  for (const PointObservation& o : data.points)
    problem.AddResidualBlock(new PointCost(initial, o), makeLoss(options), theta.data());
  for (const ConstrainedMotionData& c : data.constrained)
    for (std::size_t k = 0; k < c.stations.size(); ++k)
      problem.AddResidualBlock(new GaugeCost(initial, c, k), makeLoss(options), theta.data());
  for (Eigen::Index k = 0; k < out.identifiability.null_space.cols(); ++k) {
    HexapodParameterVector n = HexapodParameterVector::Zero();
    for (Eigen::Index c = 0; c < n_free; ++c)
      n(out.free_indices[static_cast<std::size_t>(c)]) = out.identifiability.null_space(c, k);
    problem.AddResidualBlock(new NullSpacePrior(n, out.initial), nullptr, theta.data());
  }
  if (n_free < kHexapodParameters) {
    std::vector<int> fixed;
    for (int k = 0; k < kHexapodParameters; ++k)
      if (!options.free[static_cast<std::size_t>(k)]) fixed.push_back(k);
    problem.SetManifold(theta.data(), new ceres::SubsetManifold(kHexapodParameters, fixed));
  }
  ceres::Solver::Options solver;
  solver.minimizer_type = ceres::TRUST_REGION;
  solver.trust_region_strategy_type = ceres::LEVENBERG_MARQUARDT;
  solver.linear_solver_type = ceres::DENSE_QR;
  solver.max_num_iterations = options.max_iterations;
  solver.function_tolerance = options.function_tolerance;
  solver.gradient_tolerance = options.gradient_tolerance;
  solver.parameter_tolerance = options.parameter_tolerance;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  const auto t0 = std::chrono::steady_clock::now();
  ceres::Solve(solver, &problem, &summary);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out.converged = summary.termination_type == ceres::CONVERGENCE;
  out.termination = summary.message;
  out.iterations = static_cast<int>(summary.iterations.size()) - 1;
  out.initial_cost = summary.initial_cost;
  out.final_cost = summary.final_cost;
  out.parameters = theta;

  const HexapodModel estimated = withHexapodParameters(initial, theta);
  out.after = residualStatistics(estimated, data);
  // Covariance σ²(JᵀJ)⁺ on the identifiable subspace of the free parameters.
  const Eigen::MatrixXd J1 = identificationJacobian(estimated, data);
  Eigen::MatrixXd J1_free(J1.rows(), n_free);
  for (Eigen::Index c = 0; c < n_free; ++c)
    J1_free.col(c) = J1.col(out.free_indices[static_cast<std::size_t>(c)]);
  const int rank = out.identifiability.rank;
  const double dof = static_cast<double>(out.after.equations - rank);
  out.sigma = options.measurement_sigma > 0.0
                  ? options.measurement_sigma
                  : (dof > 0 ? out.after.rms * std::sqrt(out.after.equations / dof) : 0.0);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J1_free, Eigen::ComputeThinV);
  Eigen::MatrixXd cov_free = Eigen::MatrixXd::Zero(n_free, n_free);
  for (int k = 0; k < rank && k < svd.singularValues().size(); ++k) {
    const double s = svd.singularValues()(k);
    cov_free += (svd.matrixV().col(k) / (s * s)) * svd.matrixV().col(k).transpose();
  }
  cov_free *= out.sigma * out.sigma;
  out.covariance = Eigen::MatrixXd::Zero(kHexapodParameters, kHexapodParameters);
  for (Eigen::Index a = 0; a < n_free; ++a)
    for (Eigen::Index b = 0; b < n_free; ++b)
      out.covariance(out.free_indices[static_cast<std::size_t>(a)],
                     out.free_indices[static_cast<std::size_t>(b)]) = cov_free(a, b);
  out.standard_deviation = out.covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  return out;
}

}  // namespace pkm::calibration
