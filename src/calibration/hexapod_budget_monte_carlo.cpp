// GUM Supplement 1 propagation of a hexapod calibration's budgets: the calibration re-fitted on
// perturbed observations with the adaptive stopping rule of JCGM 101:2008 §7.9
// (calibration/hexapod_budget.hpp).
#include <fmt/format.h>

#include <chrono>
#include <cmath>
#include <map>
#include <optional>

#include "detail/budget_monte_carlo.hpp"
#include "detail/hexapod_errors.hpp"
#include "detail/noise_stream.hpp"
#include "pkm/calibration/hexapod_budget.hpp"
#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"

namespace pkm::calibration {
namespace {

/// The unknowns of one trial's estimate, in the budgets' order (free parameters, frame, backlash).
Eigen::VectorXd unknownsOf(const HexapodCalibrationSummary& s,
                           const HexapodCalibrationSummary& fit,
                           Eigen::Index n) {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  Eigen::Index v = 0;
  for (const int k : fit.free_indices) x(v++) = s.parameters(k);
  if (fit.measurement_frame && s.measurement_frame) {
    x.segment<3>(v) = s.measurement_frame->translation() - fit.measurement_frame->translation();
    x.segment<3>(v + 3) = geometry::so3Log(s.measurement_frame->linear() *
                                           fit.measurement_frame->linear().transpose());
    v += 6;
  }
  if (fit.backlash && s.backlash) x.segment<6>(v) = *s.backlash;
  return x;
}

}  // namespace

bool BudgetMonteCarloOptions::isValid(std::string* why) const {
  const auto fail = [&](std::string reason) {
    if (why) *why = std::move(reason);
    return false;
  };
  if (batch < 10) return fail(fmt::format("Monte Carlo: batch must be >= 10, got {}", batch));
  if (max_trials < 2 * batch)
    return fail(fmt::format("Monte Carlo: max_trials must be >= 2 x batch, got {}", max_trials));
  if (significant_digits < 1 || significant_digits > 3)
    return fail("Monte Carlo: significant_digits must be 1, 2 or 3");
  if (threads < 0) return fail("Monte Carlo: threads must be >= 0");
  if (!(coverage_probability > 0.0 && coverage_probability < 1.0))
    return fail("Monte Carlo: coverage_probability must be in (0, 1)");
  return true;
}

BudgetMonteCarloResult hexapodBudgetMonteCarlo(const kinematics::HexapodModel& initial,
                                               const HexapodCalibrationData& data,
                                               const HexapodCalibrationSummary& fit,
                                               const HexapodCalibrationOptions& calibration,
                                               const metrology::UncertaintySources& sources,
                                               const HexapodParameterUncertainty& linear,
                                               const BudgetMonteCarloOptions& options) {
  std::string why;
  PKM_CHECK(options.isValid(&why), "{}", why);
  PKM_CHECK(sources.isValid(&why), "{}", why);
  const auto t0 = std::chrono::steady_clock::now();
  const kinematics::HexapodModel estimate = withHexapodParameters(initial, fit.parameters);
  const HexapodCalibrationData base = detail::predictedData(estimate, data, fit.measurement_frame);
  std::vector<detail::CoordinateSource> inputs =
      detail::hexapodCoordinateSources(data, sources, initial, fit.backlash.has_value());
  if (linear.linear.fit_sigma > 0.0) {
    detail::CoordinateSource typeA;
    typeA.contributor.distribution = metrology::Distribution::kNormal;
    typeA.coordinates = detail::residualCoordinates(data, linear.linear.fit_sigma);
    inputs.push_back(std::move(typeA));
  }
  const auto n = static_cast<Eigen::Index>(linear.linear.budgets.size());
  std::vector<bool> uncertain;
  for (const metrology::UncertaintyBudget& b : linear.linear.budgets)
    uncertain.push_back(b.combinedStandardUncertainty() > 0.0);

  const detail::BudgetSamples samples = detail::runBudgetMonteCarlo(
      n,
      uncertain,
      options,
      [&](int /*k*/,
          detail::GaussianStream& normal,
          detail::UniformStream& uniform) -> std::optional<Eigen::VectorXd> {
        HexapodCalibrationData d = base;
        for (const detail::CoordinateSource& s : inputs) {
          // A group's error is drawn once (unit standard uncertainty) and scaled per coordinate.
          std::map<int, double> shared;
          for (const detail::MeasuredCoordinate& c : s.coordinates) {
            if (c.group < 0) {
              detail::perturbMeasurement(
                  d, c, detail::drawError(s.contributor.distribution, c.u, uniform, normal));
              continue;
            }
            const auto [it, added] = shared.emplace(c.group, 0.0);
            if (added)
              it->second = detail::drawError(s.contributor.distribution, 1.0, uniform, normal);
            detail::perturbMeasurement(d, c, c.u * it->second);
          }
        }
        // The prior's centre (the machine file's free parameters) is an input too: drawn from
        // N(θ₀, σ²), σ as the linear budget's prior contributor states it.
        kinematics::HexapodModel start = initial;
        if (calibration.parameter_prior_sigma > 0.0) {
          const double sigma = calibration.prior_uncertainty > 0.0
                                   ? calibration.prior_uncertainty
                                   : calibration.parameter_prior_sigma;
          HexapodParameterVector theta0 = hexapodParameters(initial);
          for (const int k : fit.free_indices) theta0(k) += sigma * normal();
          start = withHexapodParameters(initial, theta0);
        }
        try {
          return unknownsOf(calibrateHexapod(start, d, calibration), fit, n);
        } catch (const InvalidArgument&) {
          return std::nullopt;  // a failed re-fit: counted as a failure, its column dropped
        }
      });
  BudgetMonteCarloResult out = detail::budgetResult(
      samples, options.coverage_probability, linear.parameter_indices, kHexapodParameters);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace pkm::calibration
