#include "detail/numeric_fit.hpp"

#include <ceres/ceres.h>

#include <Eigen/SVD>
#include <cmath>

#include "detail/least_squares.hpp"
#include "pkm/core/error.hpp"

namespace pkm::calibration::detail {
namespace {

/// Central differences of one block over the free unknowns.
bool blockJacobian(const NumericProblem& p,
                   const Eigen::VectorXd& theta,
                   std::size_t b,
                   const std::vector<bool>* free,
                   double* r,
                   Eigen::MatrixXd* J) {
  if (!p.residual(theta, b, r)) return false;
  if (J == nullptr) return true;
  const int rows = p.rows[b];
  J->setZero(rows, p.unknowns());
  Eigen::VectorXd t = theta;
  Eigen::VectorXd plus(rows), minus(rows);
  for (Eigen::Index c = 0; c < p.unknowns(); ++c) {
    if (free != nullptr && !(*free)[static_cast<std::size_t>(c)]) continue;
    const double h = p.step(c);
    t(c) = theta(c) + h;
    const bool a = p.residual(t, b, plus.data());
    t(c) = theta(c) - h;
    const bool m = p.residual(t, b, minus.data());
    t(c) = theta(c);
    if (!a || !m) return false;
    J->col(c) = (plus - minus) / (2.0 * h);
  }
  return true;
}

class BlockCost final : public ceres::CostFunction {
 public:
  BlockCost(const NumericProblem& p, std::size_t b, const std::vector<bool>& free)
      : p_(p), b_(b), free_(free) {
    set_num_residuals(p.rows[b]);
    mutable_parameter_block_sizes()->push_back(static_cast<int>(p.unknowns()));
  }
  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const final {
    const Eigen::VectorXd theta = Eigen::Map<const Eigen::VectorXd>(parameters[0], p_.unknowns());
    Eigen::MatrixXd J;
    const bool want = jacobians != nullptr && jacobians[0] != nullptr;
    if (!blockJacobian(p_, theta, b_, &free_, residuals, want ? &J : nullptr)) return false;
    if (want) {
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> out(
          jacobians[0], p_.rows[b_], p_.unknowns());
      out = J;
    }
    return true;
  }

 private:
  const NumericProblem& p_;
  std::size_t b_;
  const std::vector<bool>& free_;
};

class Prior final : public ceres::CostFunction {
 public:
  Prior(Eigen::VectorXd n, Eigen::VectorXd theta0) : n_(std::move(n)), theta0_(std::move(theta0)) {
    set_num_residuals(1);
    mutable_parameter_block_sizes()->push_back(static_cast<int>(n_.size()));
  }
  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const final {
    const Eigen::Map<const Eigen::VectorXd> theta(parameters[0], n_.size());
    residuals[0] = n_.dot(theta - theta0_);
    if (jacobians != nullptr && jacobians[0] != nullptr) {
      Eigen::Map<Eigen::VectorXd> out(jacobians[0], n_.size());
      out = n_;
    }
    return true;
  }

 private:
  Eigen::VectorXd n_, theta0_;
};

ceres::LossFunction* makeLoss(RobustLoss loss, double scale) {
  switch (loss) {
    case RobustLoss::kNone:
      return nullptr;
    case RobustLoss::kHuber:
      return new ceres::HuberLoss(scale);
    case RobustLoss::kCauchy:
      return new ceres::CauchyLoss(scale);
  }
  return nullptr;
}

}  // namespace

Eigen::Index NumericProblem::equations() const {
  Eigen::Index n = 0;
  for (const int r : rows) n += r;
  return n;
}

void stackNumeric(const NumericProblem& problem,
                  const Eigen::VectorXd& theta,
                  const std::vector<bool>* free,
                  Eigen::VectorXd* r,
                  Eigen::MatrixXd* J,
                  std::vector<bool>* ok) {
  const Eigen::Index m = problem.equations();
  if (r != nullptr) r->setZero(m);
  if (J != nullptr) J->setZero(m, problem.unknowns());
  if (ok != nullptr) ok->assign(problem.rows.size(), false);
  Eigen::Index row = 0;
  Eigen::VectorXd rb;
  Eigen::MatrixXd Jb;
  for (std::size_t b = 0; b < problem.rows.size(); ++b) {
    const int n = problem.rows[b];
    rb.setZero(n);
    const bool good =
        blockJacobian(problem, theta, b, free, rb.data(), J != nullptr ? &Jb : nullptr);
    if (good) {
      if (r != nullptr) r->segment(row, n) = rb;
      if (J != nullptr) J->middleRows(row, n) = Jb;
    }
    if (ok != nullptr) (*ok)[b] = good;
    row += n;
  }
}

NumericSolution solveNumeric(const NumericProblem& problem,
                             const Eigen::VectorXd& theta0,
                             const NumericOptions& options,
                             const NumericProblem* structural) {
  const Eigen::Index n = problem.unknowns();
  assert(theta0.size() == n && static_cast<Eigen::Index>(options.free.size()) == n);
  NumericSolution out;
  for (Eigen::Index k = 0; k < n; ++k)
    if (options.free[static_cast<std::size_t>(k)]) out.free_indices.push_back(static_cast<int>(k));
  const auto n_free = static_cast<Eigen::Index>(out.free_indices.size());
  PKM_CHECK(n_free > 0, "calibration: no parameter is free");
  PKM_CHECK(problem.equations() >= n_free,
            "calibration: too few observations: {} equations for {} unknowns",
            problem.equations(),
            n_free);
  const auto select = [&](const Eigen::MatrixXd& J) {
    Eigen::MatrixXd S(J.rows(), n_free);
    for (Eigen::Index c = 0; c < n_free; ++c)
      S.col(c) = J.col(out.free_indices[static_cast<std::size_t>(c)]);
    return S;
  };
  std::vector<std::string> names;
  for (const int k : out.free_indices) names.push_back(problem.names[static_cast<std::size_t>(k)]);
  Eigen::MatrixXd J0;
  stackNumeric(
      structural != nullptr ? *structural : problem, theta0, &options.free, nullptr, &J0, nullptr);
  out.identifiability = analyseIdentifiability(select(J0), names, options.identifiability);

  Eigen::VectorXd theta = theta0;
  ceres::Problem cp;
  for (std::size_t b = 0; b < problem.rows.size(); ++b)
    cp.AddResidualBlock(new BlockCost(problem, b, options.free),
                        makeLoss(options.loss, options.loss_scale),
                        theta.data());
  for (Eigen::Index k = 0; k < out.identifiability.null_space.cols(); ++k) {
    Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
    for (Eigen::Index c = 0; c < n_free; ++c)
      v(out.free_indices[static_cast<std::size_t>(c)]) = out.identifiability.null_space(c, k);
    cp.AddResidualBlock(new Prior(v, theta0), nullptr, theta.data());
  }
  detail::holdFixedParameters(cp, theta.data(), static_cast<int>(n), options.free);
  solveLeastSquares(cp,
                    {options.max_iterations,
                     options.function_tolerance,
                     options.gradient_tolerance,
                     options.parameter_tolerance})
      .copyTo(out);
  out.theta = theta;

  // Covariance σ²(JᵀJ)⁺ of the free unknowns on the identifiable subspace.
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  stackNumeric(problem, theta, &options.free, &r, &J, nullptr);
  const Eigen::MatrixXd Js = select(J);
  const int rank = out.identifiability.rank;
  const double dof = static_cast<double>(r.size() - rank);
  out.sigma = options.measurement_sigma > 0.0 ? options.measurement_sigma
              : dof > 0.0                     ? std::sqrt(r.squaredNorm() / dof)
                                              : 0.0;
  // Column-scaled, as the identifiability analysis: the rank counts in the scaled space.
  Eigen::VectorXd scale = Js.colwise().norm().transpose();
  for (Eigen::Index c = 0; c < scale.size(); ++c)
    if (scale(c) == 0.0) scale(c) = 1.0;
  const Eigen::MatrixXd Jn = Js * scale.cwiseInverse().asDiagonal();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(Jn, Eigen::ComputeThinV);
  const Eigen::VectorXd& s = svd.singularValues();
  Eigen::MatrixXd cov_free = Eigen::MatrixXd::Zero(n_free, n_free);
  for (Eigen::Index k = 0; k < std::min<Eigen::Index>(rank, s.size()); ++k)
    if (s(k) > 0.0)
      cov_free += svd.matrixV().col(k) * svd.matrixV().col(k).transpose() / (s(k) * s(k));
  cov_free = scale.cwiseInverse().asDiagonal() * cov_free * scale.cwiseInverse().asDiagonal();
  cov_free *= out.sigma * out.sigma;
  out.covariance = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index a = 0; a < n_free; ++a)
    for (Eigen::Index b = 0; b < n_free; ++b)
      out.covariance(out.free_indices[static_cast<std::size_t>(a)],
                     out.free_indices[static_cast<std::size_t>(b)]) = cov_free(a, b);
  out.standard_deviation = out.covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  return out;
}

}  // namespace pkm::calibration::detail
