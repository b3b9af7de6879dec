// Uncertainty budgets of ISO 230-4 circular tests (metrology/circular_uncertainty.hpp).
#include "pkm/metrology/circular_uncertainty.hpp"

#include <fmt/format.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>

#include "metrology/detail/length_contributor.hpp"
#include "pkm/core/error.hpp"

namespace pkm::metrology {
namespace {

const double kSqrt2 = std::sqrt(2.0);

/// The bar's length change by the temperature change during the test, α·R·ΔT (rectangular): it
/// moves every reading after it, so it acts on a range and on a single reading alike.
UncertaintyContributor barTemperatureChange(double radius, const MeasurementEnvironment& e) {
  return detail::lengthContributor(
      "bar temperature change during the test",
      e.expansion_coefficient_per_k * radius * e.air_temperature_variation_k,
      Distribution::kRectangular,
      1.0,
      "environment: alpha x radius x temperature change");
}

/// One run (or both together) about a centre: radial distances in the order read and the
/// indices of the largest and smallest.
struct Radii {
  std::vector<double> r;
  std::size_t max = 0;
  std::size_t min = 0;
};

Radii radiiAbout(std::span<const Point2> a, std::span<const Point2> b, const Point2& c) {
  Radii out;
  out.r.reserve(a.size() + b.size());
  for (const Point2& p : a) out.r.push_back((p - c).norm());
  for (const Point2& p : b) out.r.push_back((p - c).norm());
  const auto [lo, hi] = std::minmax_element(out.r.begin(), out.r.end());
  out.min = static_cast<std::size_t>(lo - out.r.begin());
  out.max = static_cast<std::size_t>(hi - out.r.begin());
  return out;
}

const Point2& pointAt(std::span<const Point2> a, std::span<const Point2> b, std::size_t i) {
  return i < a.size() ? a[i] : b[i - a.size()];
}

/// σ of the noise of one or two runs (each run's successive differences, pooled by count).
double noiseSigma(std::span<const Point2> a, std::span<const Point2> b, const Point2& c) {
  double sum = 0.0;
  double dof = 0.0;
  for (const std::span<const Point2> run : {a, b}) {
    if (run.size() < 3) continue;
    std::vector<double> r;
    r.reserve(run.size());
    for (const Point2& p : run) r.push_back((p - c).norm());
    const double s = successiveDifferenceSigma(r);
    const double n = static_cast<double>(run.size()) - 2.0;
    sum += s * s * n;
    dof += n;
  }
  return dof > 0.0 ? std::sqrt(sum / dof) : 0.0;
}

/// The instrument's, the noise's and the temperature's contributors to a radial range read at
/// two points (G, G(b)) or to a difference of two readings at one angle (H: `common_sensor`, the
/// sensor's accuracy is the same for both and cancels).
void addTwoReadingContributors(UncertaintyBudget& b,
                               double sigma,
                               double radius,
                               std::size_t points,
                               bool common_sensor,
                               const UncertaintySources& src) {
  if (!common_sensor)
    addContributor(b,
                   detail::lengthContributor("ballbar sensor accuracy",
                                             src.ballbar.sensor_accuracy_mm,
                                             Distribution::kRectangular,
                                             kSqrt2,
                                             "instrument specification, two readings"));
  addContributor(b,
                 detail::lengthContributor("ballbar resolution",
                                           src.ballbar.resolution_mm / 2.0,
                                           Distribution::kRectangular,
                                           kSqrt2,
                                           "instrument specification, two readings"));
  addContributor(b,
                 detail::lengthContributor(
                     "non-repeatable noise",
                     sigma,
                     Distribution::kNormal,
                     kSqrt2,
                     fmt::format("data: successive differences of {} readings", points)));
  const MeasurementEnvironment& e = src.environment;
  addContributor(b, barTemperatureChange(radius, e));
}

/// The least-squares centre's covariance σ²(JᵀJ)⁻¹ of the points (rows [u_k, 1]) and the first-
/// order sensitivity of r_max − r_min to it: ∂(r_i − r_j)/∂c = −(u_i − u_j).
void addCentreContributors(UncertaintyBudget& b,
                           std::span<const Point2> a,
                           std::span<const Point2> bb,
                           const Point2& c,
                           const Radii& radii,
                           double sigma) {
  Eigen::Matrix3d normal = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < a.size() + bb.size(); ++i) {
    const Point2 u = (pointAt(a, bb, i) - c).normalized();
    const Eigen::Vector3d row(u.x(), u.y(), 1.0);
    normal += row * row.transpose();
  }
  const Eigen::Matrix2d cov =
      (sigma * sigma) * normal.inverse().topLeftCorner<2, 2>();  // centre part
  if (!cov.allFinite() || sigma == 0.0) return;
  const Point2 ui = (pointAt(a, bb, radii.max) - c).normalized();
  const Point2 uj = (pointAt(a, bb, radii.min) - c).normalized();
  const Point2 sens = -(ui - uj);
  const std::size_t first = b.contributors.size();
  const double sx = std::sqrt(cov(0, 0));
  const double sy = std::sqrt(cov(1, 1));
  addContributor(b,
                 detail::lengthContributor("least-squares centre x",
                                           sx,
                                           Distribution::kNormal,
                                           sens.x(),
                                           "data: LSC covariance from the noise"));
  addContributor(b,
                 detail::lengthContributor("least-squares centre y",
                                           sy,
                                           Distribution::kNormal,
                                           sens.y(),
                                           "data: LSC covariance from the noise"));
  if (b.contributors.size() == first + 2 && sx > 0.0 && sy > 0.0)
    b.correlations.push_back({first, first + 1, std::clamp(cov(0, 1) / (sx * sy), -1.0, 1.0)});
}

UncertaintyBudget rangeBudget(const char* quantity,
                              double value,
                              std::span<const Point2> a,
                              std::span<const Point2> b,
                              const Point2& centre,
                              CircularCentre centre_kind,
                              const UncertaintySources& src) {
  UncertaintyBudget budget;
  budget.quantity = quantity;
  budget.unit = "mm";
  budget.value = value;
  budget.coverage_factor = src.coverage_factor;
  const Radii radii = radiiAbout(a, b, centre);
  const double sigma = noiseSigma(a, b, centre);
  double mean = 0.0;
  for (const double r : radii.r) mean += r;
  mean /= static_cast<double>(radii.r.size());
  addTwoReadingContributors(budget, sigma, mean, radii.r.size(), false, src);
  // The least-squares centre comes from the same noisy data; the minimum-zone width is stationary
  // at its own centre, and a nominal centre is given, not estimated.
  if (centre_kind == CircularCentre::kLeastSquares)
    addCentreContributors(budget, a, b, centre, radii, sigma);
  return budget;
}

/// F_max or F_min of one run: one reading against the nominal radius, so the bar's absolute length
/// counts (its calibration and its temperature), as do the sensor and the noise at that reading.
UncertaintyBudget radialBudget(const std::string& quantity,
                               double value,
                               double radius,
                               double sigma,
                               const UncertaintySources& src) {
  UncertaintyBudget b;
  b.quantity = quantity;
  b.unit = "mm";
  b.value = value;
  b.coverage_factor = src.coverage_factor;
  addContributor(b,
                 detail::lengthContributor("ballbar length calibration",
                                           src.ballbar.length_uncertainty_mm,
                                           Distribution::kNormal,
                                           1.0,
                                           "calibrator certificate (k = 2)",
                                           2.0));
  addContributor(b,
                 detail::lengthContributor("ballbar sensor accuracy",
                                           src.ballbar.sensor_accuracy_mm,
                                           Distribution::kRectangular,
                                           1.0,
                                           "instrument specification"));
  addContributor(b,
                 detail::lengthContributor("ballbar resolution",
                                           src.ballbar.resolution_mm / 2.0,
                                           Distribution::kRectangular,
                                           1.0,
                                           "instrument specification"));
  addContributor(b,
                 detail::lengthContributor("non-repeatable noise",
                                           sigma,
                                           Distribution::kNormal,
                                           1.0,
                                           "data: successive differences"));
  const MeasurementEnvironment& e = src.environment;
  addContributor(b,
                 detail::lengthContributor("expansion coefficient of the bar",
                                           e.expansion_coefficient_accuracy_per_k * radius *
                                               std::abs(e.material_temperature_c - 20.0),
                                           Distribution::kRectangular,
                                           1.0,
                                           "environment: u(alpha) x radius x |t - 20 C|"));
  addContributor(b, barTemperatureChange(radius, e));
  return b;
}

}  // namespace

double successiveDifferenceSigma(std::span<const double> values) {
  if (values.size() < 3) return 0.0;
  const std::size_t n = values.size() - 1;  // differences
  double mean = 0.0;
  for (std::size_t k = 0; k < n; ++k) mean += values[k + 1] - values[k];
  mean /= static_cast<double>(n);
  double sum = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double d = values[k + 1] - values[k] - mean;
    sum += d * d;
  }
  return std::sqrt(sum / (2.0 * static_cast<double>(n - 1)));
}

std::vector<UncertaintyBudget> circularTestUncertainty(std::span<const Point2> cw,
                                                       std::span<const Point2> ccw,
                                                       const CircularTestResult& result,
                                                       const UncertaintySources& sources) {
  std::string why;
  PKM_CHECK(sources.isValid(&why), "uncertainty sources: {}", why);
  PKM_CHECK(cw.size() >= 4 && ccw.size() >= 4,
            "circular test budgets need at least 4 points per run (got {} and {})",
            cw.size(),
            ccw.size());
  const std::span<const Point2> none;
  std::vector<UncertaintyBudget> out;
  out.push_back(rangeBudget(
      "G_cw", result.cw.circular_deviation, cw, none, result.cw.center, result.centre, sources));
  out.push_back(rangeBudget("G_ccw",
                            result.ccw.circular_deviation,
                            ccw,
                            none,
                            result.ccw.center,
                            result.centre,
                            sources));
  out.push_back(rangeBudget("G_bidirectional",
                            result.bidirectional_deviation,
                            cw,
                            ccw,
                            result.common_center,
                            result.centre,
                            sources));
  // H: one reading of each run at the same angle about the common centre.
  UncertaintyBudget h;
  h.quantity = "H";
  h.unit = "mm";
  h.value = result.hysteresis;
  h.coverage_factor = sources.coverage_factor;
  const double sigma = noiseSigma(cw, ccw, result.common_center);
  addTwoReadingContributors(h,
                            sigma,
                            0.5 * (result.cw.radius + result.ccw.radius),
                            cw.size() + ccw.size(),
                            true,
                            sources);
  out.push_back(std::move(h));
  if (result.cw.radial_deviation_max) {
    for (const auto& [run, points, name] :
         {std::tuple{&result.cw, cw, "cw"}, std::tuple{&result.ccw, ccw, "ccw"}}) {
      const double s = noiseSigma(points, none, run->center);
      out.push_back(radialBudget(
          fmt::format("F_max_{}", name), *run->radial_deviation_max, run->radius, s, sources));
      out.push_back(radialBudget(
          fmt::format("F_min_{}", name), *run->radial_deviation_min, run->radius, s, sources));
    }
  }
  return out;
}

}  // namespace pkm::metrology
