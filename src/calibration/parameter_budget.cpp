// Uncertainty budgets of calibrated parameters (calibration/parameter_budget.hpp).
#include "pkm/calibration/parameter_budget.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

#include "pkm/core/error.hpp"

namespace pkm::calibration {

Eigen::MatrixXd identificationInverse(const Eigen::MatrixXd& J,
                                      int rank,
                                      Eigen::Index observation_rows) {
  PKM_CHECK(rank >= 0, "identification inverse: rank must be >= 0, got {}", rank);
  PKM_CHECK(observation_rows >= 0 && observation_rows <= J.rows(),
            "identification inverse: {} observation rows of a {}-row Jacobian",
            observation_rows,
            J.rows());
  if (J.size() == 0) return Eigen::MatrixXd::Zero(J.cols(), observation_rows);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& s = svd.singularValues();
  Eigen::Index r = 0;  // the leading singular values used: at most `rank`, all > 0
  while (r < std::min<Eigen::Index>(rank, s.size()) && s(r) > 0.0) ++r;
  // Σ_k v_k·u_kᵀ/s_k over k < r, as one product (V_r·Σ_r⁻¹)·U_rᵀ of the observation rows.
  const Eigen::MatrixXd V_scaled =
      svd.matrixV().leftCols(r) * s.head(r).cwiseInverse().asDiagonal();
  return V_scaled * svd.matrixU().topLeftCorner(observation_rows, r).transpose();
}

bool ParameterBudgetInput::isValid(std::string* why) const {
  const auto fail = [&](std::string reason) {
    if (why) *why = std::move(reason);
    return false;
  };
  const auto n = static_cast<Eigen::Index>(names.size());
  if (static_cast<Eigen::Index>(units.size()) != n || values.size() != n || inverse.rows() != n)
    return fail(fmt::format(
        "parameter budgets: {} names, {} units, {} values and {} inverse rows must agree",
        names.size(),
        units.size(),
        values.size(),
        inverse.rows()));
  for (const ObservationErrorSource& s : sources)
    if (s.effect.rows() != inverse.cols())
      return fail(fmt::format("parameter budgets: source '{}' has {} rows for {} residuals",
                              s.contributor.name,
                              s.effect.rows(),
                              inverse.cols()));
  if (prior_inverse.size() > 0 &&
      (prior_inverse.rows() != n || prior.effect.rows() != prior_inverse.cols()))
    return fail(
        fmt::format("parameter budgets: the prior has a {} x {} inverse and {} effect rows "
                    "for {} unknowns",
                    prior_inverse.rows(),
                    prior_inverse.cols(),
                    prior.effect.rows(),
                    n));
  if (!(std::isfinite(residual_sigma) && residual_sigma >= 0.0))
    return fail("parameter budgets: the residual sigma must be finite and >= 0");
  if (!(std::isfinite(coverage_factor) && coverage_factor > 0.0))
    return fail("parameter budgets: the coverage factor must be > 0");
  return true;
}

ParameterUncertainty parameterBudgets(const ParameterBudgetInput& in) {
  std::string why;
  PKM_CHECK(in.isValid(&why), "{}", why);
  const Eigen::Index n = in.inverse.rows(), m = in.inverse.cols();
  ParameterUncertainty out;
  out.covariance = Eigen::MatrixXd::Zero(n, n);
  // Per source: S_s = J⁺·E_s (n × q); parameter k's sensitivity is the norm of row k.
  std::vector<Eigen::MatrixXd> effect_on_theta;
  double instrument_variance = 0.0;
  for (const ObservationErrorSource& s : in.sources) {
    const double u = s.contributor.standardUncertainty();
    effect_on_theta.push_back(in.inverse * s.effect);
    out.covariance += u * u * effect_on_theta.back() * effect_on_theta.back().transpose();
    instrument_variance += u * u * s.effect.squaredNorm();
  }
  out.instrument_sigma = m > 0 ? std::sqrt(instrument_variance / static_cast<double>(m)) : 0.0;
  const double excess =
      in.residual_sigma * in.residual_sigma - out.instrument_sigma * out.instrument_sigma;
  out.fit_sigma = std::sqrt(std::max(0.0, excess));
  out.covariance += out.fit_sigma * out.fit_sigma * in.inverse * in.inverse.transpose();
  const bool has_prior = in.prior_inverse.size() > 0;
  Eigen::MatrixXd prior_on_theta;
  if (has_prior) {
    const double u = in.prior.contributor.standardUncertainty();
    prior_on_theta = in.prior_inverse * in.prior.effect;
    out.covariance += u * u * prior_on_theta * prior_on_theta.transpose();
  }

  for (Eigen::Index k = 0; k < n; ++k) {
    metrology::UncertaintyBudget b;
    b.quantity = in.names[static_cast<std::size_t>(k)];
    b.unit = in.units[static_cast<std::size_t>(k)];
    b.value = in.values(k);
    b.coverage_factor = in.coverage_factor;
    for (std::size_t s = 0; s < in.sources.size(); ++s) {
      metrology::UncertaintyContributor c = in.sources[s].contributor;
      c.sensitivity = effect_on_theta[s].row(k).norm();
      metrology::addContributor(b, std::move(c));
    }
    metrology::UncertaintyContributor fit;
    fit.name = "fit residuals beyond the instrument (Type A)";
    fit.value = out.fit_sigma;
    fit.unit = in.residual_unit;
    fit.distribution = metrology::Distribution::kNormal;
    fit.normal_k = 1.0;
    fit.sensitivity = in.inverse.row(k).norm();
    fit.source = fmt::format("residual sigma {:.3g} {} of the fit, less the instrument's {:.3g}",
                             in.residual_sigma,
                             in.residual_unit,
                             out.instrument_sigma);
    metrology::addContributor(b, std::move(fit));
    if (has_prior) {
      metrology::UncertaintyContributor prior = in.prior.contributor;
      prior.sensitivity = prior_on_theta.row(k).norm();
      metrology::addContributor(b, std::move(prior));
    }
    out.budgets.push_back(std::move(b));
  }
  return out;
}

double positionExpandedUncertainty(const Eigen::MatrixXd& J,
                                   const Eigen::MatrixXd& covariance,
                                   double coverage_factor) {
  PKM_CHECK(covariance.rows() == covariance.cols() && J.cols() == covariance.rows(),
            "position uncertainty: a {}x{} Jacobian and a {}x{} covariance",
            J.rows(),
            J.cols(),
            covariance.rows(),
            covariance.cols());
  PKM_CHECK(coverage_factor > 0.0, "position uncertainty: the coverage factor must be > 0");
  const Eigen::MatrixXd S = J * covariance * J.transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (S + S.transpose()));
  const double top = eig.eigenvalues().size() > 0 ? eig.eigenvalues().maxCoeff() : 0.0;
  return coverage_factor * std::sqrt(std::max(0.0, top));
}

}  // namespace pkm::calibration
