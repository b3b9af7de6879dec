// Uncertainty budgets of straightness, parallelism and circles (metrology/profile_uncertainty.hpp).
#include "pkm/metrology/profile_uncertainty.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "metrology/detail/length_contributor.hpp"
#include "pkm/core/error.hpp"

namespace pkm::metrology {
namespace {

void checkSources(const UncertaintySources& sources) {
  std::string why;
  PKM_CHECK(sources.isValid(&why), "uncertainty sources: {}", why);
}

/// The straightness optics' accuracy a + b·|reading| + c·L² (mm) over a length L (mm).
double opticsAccuracy(const LaserInterferometer& laser, double reading_mm, double length_mm) {
  const double length_m = length_mm / 1000.0;
  return laser.straightness_accuracy_mm + laser.straightness_relative * std::abs(reading_mm) +
         laser.straightness_length_mm_per_m2 * length_m * length_m;
}

/// The largest |x| (0 for none): where the optics' %-of-reading term is evaluated.
double largestMagnitude(std::span<const double> x) {
  double m = 0.0;
  for (const double v : x) m = std::max(m, std::abs(v));
  return m;
}

double span(std::span<const double> x) {
  const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
  return *hi - *lo;
}

/// Pooled standard deviation of readings about their per-position means and the mean number of
/// readings per position; {0, 1} when no position repeats.
std::pair<double, double> pooledScatter(std::span<const double> position,
                                        std::span<const double> deviation) {
  std::map<double, std::vector<double>> groups;
  for (std::size_t k = 0; k < position.size(); ++k) groups[position[k]].push_back(deviation[k]);
  double squares = 0.0;
  std::size_t dof = 0;
  for (const auto& [p, values] : groups) {
    double mean = 0.0;
    for (double v : values) mean += v;
    mean /= static_cast<double>(values.size());
    for (double v : values) squares += (v - mean) * (v - mean);
    dof += values.size() - 1;
  }
  if (dof == 0) return {0.0, 1.0};
  return {std::sqrt(squares / static_cast<double>(dof)),
          static_cast<double>(position.size()) / static_cast<double>(groups.size())};
}

/// Standard error of a least-squares slope: s_r / √Σ(u − ū)².
double slopeStandardError(const SlopeRun& run) {
  const std::size_t n = run.position.size();
  PKM_CHECK(n >= 3 && run.residual.size() == n,
            "parallelism uncertainty: a run needs >= 3 points and one residual per point");
  double mean = 0.0;
  for (double u : run.position) mean += u;
  mean /= static_cast<double>(n);
  double sxx = 0.0, sr = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    sxx += (run.position[k] - mean) * (run.position[k] - mean);
    sr += run.residual[k] * run.residual[k];
  }
  PKM_CHECK(sxx > 0.0, "parallelism uncertainty: a run's positions are all equal");
  return std::sqrt(sr / static_cast<double>(n - 2) / sxx);
}

/// The budget of a least-squares circle's radius R (mm; lsc of N >= 4 points): the fit's
/// s/√N, the stylus radius calibration, the probe's 2D form, and the ring's temperature and
/// expansion coefficient.
UncertaintyBudget circleRadiusBudget(const CircleFit& lsc, const UncertaintySources& src) {
  const std::size_t n = lsc.residuals.size();
  const TouchProbe& probe = src.probe;
  const MeasurementEnvironment& env = src.environment;
  const double R = lsc.circle.radius;
  const double s = lsc.rms * std::sqrt(static_cast<double>(n) / static_cast<double>(n - 3));
  UncertaintyBudget radius = detail::lengthBudget("radius", R, src.coverage_factor);
  addContributor(radius,
                 detail::lengthContributor("least-squares fit (s/sqrt(N))",
                                           s / std::sqrt(static_cast<double>(n)),
                                           Distribution::kNormal,
                                           1.0,
                                           "test data"));
  addContributor(radius,
                 detail::lengthContributor("stylus radius calibration",
                                           probe.stylus_radius_uncertainty_mm,
                                           Distribution::kNormal,
                                           1.0,
                                           "instrument",
                                           2.0));
  addContributor(radius,
                 detail::lengthContributor("probe form error (2D)",
                                           probe.form_2d_mm,
                                           Distribution::kRectangular,
                                           1.0,
                                           "instrument"));
  UncertaintyContributor temperature =
      detail::lengthContributor("ring temperature",
                                src.laser.material_temperature_accuracy_k,
                                Distribution::kRectangular,
                                R * env.expansion_coefficient_per_k,
                                "environment");
  temperature.unit = "K";
  addContributor(radius, temperature);
  UncertaintyContributor alpha =
      detail::lengthContributor("expansion coefficient",
                                env.expansion_coefficient_accuracy_per_k,
                                Distribution::kRectangular,
                                R * std::abs(env.material_temperature_c - 20.0),
                                "environment");
  alpha.unit = "1/K";
  addContributor(radius, alpha);
  return radius;
}

/// The budget of roundness `name` (`value`, mm) from `n` probed points: the probe's
/// repeatability and form at two points, the master ring's form, and the probe noise's raising
/// of a range.
UncertaintyBudget circleRoundnessBudget(const char* name,
                                        double value,
                                        std::size_t n,
                                        const TouchProbe& probe,
                                        double coverage_factor) {
  UncertaintyBudget b = detail::lengthBudget(name, value, coverage_factor);
  addContributor(b,
                 detail::lengthContributor("probe repeatability (two points)",
                                           probe.repeatability_2sigma_mm,
                                           Distribution::kNormal,
                                           std::sqrt(2.0),
                                           "instrument",
                                           2.0));
  addContributor(b,
                 detail::lengthContributor("probe form error (two points)",
                                           probe.form_2d_mm,
                                           Distribution::kRectangular,
                                           std::sqrt(2.0),
                                           "instrument"));
  addContributor(b,
                 detail::lengthContributor("master ring form (certificate)",
                                           probe.ring_form_mm,
                                           Distribution::kRectangular,
                                           1.0,
                                           "artefact certificate"));
  // A roundness is a range of the residuals: the probe's noise raises it by up to the
  // expected range of N noise values, d2(N)·σ (0.68 µm for 180 points at σ = 0.125 µm). The
  // bias is one-sided and shrinks as the form grows against the noise; it is budgeted as a
  // rectangular half-width (GUM F.2.4.4) rather than subtracted.
  addContributor(b,
                 detail::lengthContributor(
                     fmt::format("probe noise raising a range of {} points (d2(N) sigma)", n),
                     expectedNormalRange(n) * probe.repeatability_2sigma_mm / 2.0,
                     Distribution::kRectangular,
                     1.0,
                     "instrument repeatability, expected range of N normal values"));
  return b;
}

}  // namespace

UncertaintyBudget straightnessUncertainty(double straightness,
                                          std::span<const double> position,
                                          std::span<const double> raw_position,
                                          std::span<const double> raw_deviation,
                                          const UncertaintySources& src) {
  checkSources(src);
  PKM_CHECK(position.size() >= 2, "straightness uncertainty: needs >= 2 positions");
  PKM_CHECK(raw_position.size() == raw_deviation.size(),
            "straightness uncertainty: {} raw positions but {} deviations",
            raw_position.size(),
            raw_deviation.size());
  UncertaintyBudget b = detail::lengthBudget("straightness", straightness, src.coverage_factor);
  addContributor(b,
                 detail::lengthContributor("straightness optics (two readings)",
                                           opticsAccuracy(src.laser, straightness, span(position)),
                                           Distribution::kRectangular,
                                           std::sqrt(2.0),
                                           "instrument"));
  const auto [s, n] = pooledScatter(raw_position, raw_deviation);
  addContributor(b,
                 detail::lengthContributor("sampling of the two extreme means (s/sqrt(n))",
                                           s / std::sqrt(n),
                                           Distribution::kNormal,
                                           std::sqrt(2.0),
                                           "test data"));
  return b;
}

UncertaintyBudget parallelismUncertainty(double parallelism,
                                         const SlopeRun& reference,
                                         const SlopeRun& axis,
                                         const UncertaintySources& src) {
  checkSources(src);
  const double u_ref = slopeStandardError(reference);
  const double u_axis = slopeStandardError(axis);
  const double travel = span(axis.position);
  const double l_ref = span(reference.position);
  UncertaintyBudget b = detail::lengthBudget("parallelism", parallelism, src.coverage_factor);
  UncertaintyContributor slope_ref = detail::lengthContributor(
      "reference line slope (least squares)", u_ref, Distribution::kNormal, travel, "test data");
  slope_ref.degrees_of_freedom = static_cast<double>(reference.position.size()) - 2.0;
  addContributor(b, slope_ref);
  UncertaintyContributor slope_axis = detail::lengthContributor(
      "axis line slope (least squares)", u_axis, Distribution::kNormal, travel, "test data");
  slope_axis.degrees_of_freedom = static_cast<double>(axis.position.size()) - 2.0;
  addContributor(b, slope_axis);
  addContributor(b,
                 detail::lengthContributor(
                     "straightness optics, reference run",
                     opticsAccuracy(src.laser, largestMagnitude(reference.reading), l_ref),
                     Distribution::kRectangular,
                     std::sqrt(2.0) * travel / l_ref,
                     "instrument"));
  addContributor(
      b,
      detail::lengthContributor("straightness optics, axis run",
                                opticsAccuracy(src.laser, largestMagnitude(axis.reading), travel),
                                Distribution::kRectangular,
                                std::sqrt(2.0),
                                "instrument"));
  return b;
}

std::vector<UncertaintyBudget> circleUncertainty(const CircleFit& lsc,
                                                 const MinZoneCircle& mzc,
                                                 const UncertaintySources& src) {
  checkSources(src);
  const std::size_t n = lsc.residuals.size();
  PKM_CHECK(n >= 4, "circle uncertainty: needs >= 4 points, got {}", n);
  const UncertaintyBudget radius = circleRadiusBudget(lsc, src);
  std::vector<UncertaintyBudget> out{radius};
  for (const auto& [name, value] :
       {std::pair{"roundness_lsc", lsc.roundness}, std::pair{"roundness_mzc", mzc.roundness}}) {
    out.push_back(circleRoundnessBudget(name, value, n, src.probe, src.coverage_factor));
  }
  return out;
}

std::vector<UncertaintyBudget> probeOffsetUncertainty(const ProbeOffsetFit& fit,
                                                      std::span<const ProbeTouch> touches,
                                                      const UncertaintySources& src) {
  checkSources(src);
  const std::size_t n = touches.size();
  PKM_CHECK(n >= 6, "probe offset uncertainty: needs >= 6 touches, got {}", n);
  Eigen::MatrixXd J(static_cast<Eigen::Index>(n), 5);
  double squares = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const Point2 b = ballCentre(touches[k], fit.offset);
    const Eigen::Vector2d u = (b - fit.ring_center).normalized();
    const double c = std::cos(touches[k].angle), s = std::sin(touches[k].angle);
    const auto row = static_cast<Eigen::Index>(k);
    J.row(row) << -u.x(), -u.y(), u.x() * c + u.y() * s, -u.x() * s + u.y() * c, -1.0;
    const double e = (b - fit.ring_center).norm() - fit.ball_path_radius;
    squares += e * e;
  }
  const Eigen::Matrix<double, 5, 5> normal = J.transpose() * J;
  const Eigen::FullPivLU<Eigen::Matrix<double, 5, 5>> lu(normal);
  PKM_CHECK(lu.isInvertible(), "probe offset uncertainty: the touches do not separate the offset");
  const Eigen::Matrix<double, 5, 5> cov = squares / static_cast<double>(n - 5) * lu.inverse();
  std::vector<UncertaintyBudget> out;
  for (int axis = 0; axis < 2; ++axis) {
    UncertaintyBudget b = detail::lengthBudget(
        axis == 0 ? "offset_x" : "offset_y", fit.offset[axis], src.coverage_factor);
    addContributor(b,
                   detail::lengthContributor("least-squares fit (covariance)",
                                             std::sqrt(cov(2 + axis, 2 + axis)),
                                             Distribution::kNormal,
                                             1.0,
                                             "test data"));
    // The probe's lobing turns with the spindle: with four touches per turn an odd lobe count
    // (3 on a strain-gauge probe) aliases to a centre shift of the full amplitude, which the
    // 180° reversal flips, so it lands whole in the offset (it cancels only for even counts).
    addContributor(b,
                   detail::lengthContributor("probe form error (odd lobes survive the reversal)",
                                             src.probe.form_2d_mm,
                                             Distribution::kRectangular,
                                             1.0,
                                             "instrument"));
    out.push_back(std::move(b));
  }
  return out;
}

}  // namespace pkm::metrology
