// GUM Supplement 1 propagation of an Exechon calibration's budgets: the calibration re-fitted on
// perturbed points with the adaptive stopping rule of JCGM 101:2008 §7.9
// (calibration/exechon_budget.hpp).
#include <chrono>
#include <cmath>
#include <optional>

#include "detail/budget_monte_carlo.hpp"
#include "detail/exechon_predicted.hpp"
#include "detail/exechon_reading_errors.hpp"
#include "detail/hexapod_errors.hpp"
#include "pkm/calibration/exechon_budget.hpp"
#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"

namespace pkm::calibration {
namespace {

/// The unknowns of one trial's estimate in the budgets' order (free parameters, then the frame as
/// δt and the rotation vector δω of its left perturbation from the fit's frame).
Eigen::VectorXd unknownsOf(const ExechonCalibrationSummary& s,
                           const ExechonCalibrationSummary& fit,
                           Eigen::Index n) {
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  Eigen::Index v = 0;
  for (const int k : fit.free_indices) {
    if (k >= kExechonParameters) continue;
    x(v++) = s.parameters(k);
  }
  if (fit.measurement_frame && s.measurement_frame && v + 6 <= n) {
    x.segment<3>(v) = s.measurement_frame->translation() - fit.measurement_frame->translation();
    x.segment<3>(v + 3) = geometry::so3Log(s.measurement_frame->linear() *
                                           fit.measurement_frame->linear().transpose());
  }
  return x;
}

/// Per observation: the standard uncertainties of a coordinate's tracker error (rectangular,
/// half-width a + b·L), set-up repeatability and Type A scatter (both normal), model unit.
struct PointErrors {
  std::vector<double> tracker_half_width;
  double setup_sigma = 0.0;
  double type_a_sigma = 0.0;
};

PointErrors pointErrors(const ExechonCalibrationData& data,
                        const metrology::UncertaintySources& sources,
                        LengthUnit unit,
                        double fit_sigma) {
  const double per_mm = 1.0 / millimetresPer(unit);
  const metrology::LaserTrackerSpec& t = sources.tracker;
  PointErrors e;
  for (const ExechonObservation& o : data.observations) {
    const double L = data.measurement_frame ? o.point.norm() / per_mm : t.range_mm;
    e.tracker_half_width.push_back((t.accuracy_mm + t.accuracy_mm_per_m * L * 1e-3) * per_mm);
  }
  e.setup_sigma = sources.environment.setup_repeatability_mm * per_mm;
  e.type_a_sigma = fit_sigma;
  return e;
}

}  // namespace

BudgetMonteCarloResult exechonBudgetMonteCarlo(const kinematics::ExechonModel& initial,
                                               const ExechonCalibrationData& data,
                                               const ExechonCalibrationSummary& fit,
                                               const ExechonCalibrationOptions& calibration,
                                               const metrology::UncertaintySources& sources,
                                               const ExechonParameterUncertainty& linear,
                                               const BudgetMonteCarloOptions& options) {
  std::string why;
  PKM_CHECK(options.isValid(&why), "{}", why);
  PKM_CHECK(sources.isValid(&why), "{}", why);
  const auto t0 = std::chrono::steady_clock::now();
  const kinematics::ExechonModel estimate =
      withExechonParameters(initial, fit.parameters, initial.world_T_zoppi);
  const ExechonCalibrationData base =
      detail::predictedExechonData(estimate, data, fit.measurement_frame, calibration.fk);
  const PointErrors errors = pointErrors(base, sources, initial.unit, linear.linear.fit_sigma);
  const std::vector<detail::LegReadingSource> legs =
      detail::exechonLegReadingSources(estimate, base, sources, calibration.fk);
  const auto n = static_cast<Eigen::Index>(linear.linear.budgets.size());
  std::vector<bool> uncertain;
  for (const metrology::UncertaintyBudget& b : linear.linear.budgets)
    uncertain.push_back(b.combinedStandardUncertainty() > 0.0);
  constexpr double kSqrt3 = 1.7320508075688772;

  const detail::BudgetSamples samples = detail::runBudgetMonteCarlo(
      n,
      uncertain,
      options,
      [&](int /*k*/,
          detail::GaussianStream& normal,
          detail::UniformStream& uniform) -> std::optional<Eigen::VectorXd> {
        ExechonCalibrationData d = base;
        for (std::size_t i = 0; i < d.observations.size(); ++i)
          for (int c = 0; c < 3; ++c)
            d.observations[i].point(c) += detail::drawError(metrology::Distribution::kRectangular,
                                                            errors.tracker_half_width[i] / kSqrt3,
                                                            uniform,
                                                            normal) +
                                          errors.setup_sigma * normal() +
                                          errors.type_a_sigma * normal();
        // The leg readings' errors: each independent error drawn at unit standard uncertainty
        // scales its column (the change at the contributor's reference uncertainty).
        Eigen::VectorXd dq =
            Eigen::VectorXd::Zero(3 * static_cast<Eigen::Index>(d.observations.size()));
        for (const detail::LegReadingSource& s : legs) {
          Eigen::VectorXd draws(s.errors());
          for (Eigen::Index j = 0; j < draws.size(); ++j)
            draws(j) = detail::drawError(s.contributor.distribution, 1.0, uniform, normal);
          dq += s.change(draws);
        }
        for (std::size_t i = 0; i < d.observations.size(); ++i)
          d.observations[i].joints.readings += dq.segment<3>(3 * static_cast<Eigen::Index>(i));
        try {
          return unknownsOf(calibrateExechon(initial, d, calibration), fit, n);
        } catch (const InvalidArgument&) {
          return std::nullopt;  // a failed re-fit: counted as a failure, its column dropped
        }
      });
  BudgetMonteCarloResult out = detail::budgetResult(
      samples, options.coverage_probability, linear.parameter_indices, kExechonParameters);
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

}  // namespace pkm::calibration
