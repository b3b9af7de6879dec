// Squareness from diagonals, propagated linearly and by Monte Carlo
// (metrology/squareness_uncertainty.hpp).
#include "pkm/metrology/squareness_uncertainty.hpp"

#include <cmath>
#include <utility>

#include "pkm/core/error.hpp"
#include "pkm/metrology/positioning_uncertainty.hpp"
#include "pkm/metrology/recorded_conditions.hpp"

namespace pkm::metrology {
namespace {

/// The length over which the common scale is stated, mm (the result is relative).
constexpr double kScaleLengthMm = 1000.0;

UncertaintyContributor input(std::string name,
                             double value,
                             std::string unit,
                             Distribution distribution,
                             std::string source) {
  UncertaintyContributor c;
  c.name = std::move(name);
  c.value = value;
  c.unit = std::move(unit);
  c.distribution = distribution;
  c.source = std::move(source);
  return c;
}

/// The relative standard uncertainty of a laser length from the scale-like contributors only
/// (no cosine, Abbe, set-up, dead path or E_VE: those differ from line to line or are absent).
double commonScale(const UncertaintySources& src) {
  UncertaintySources scale_only = src;
  scale_only.environment.misalignment_rad = 0.0;
  scale_only.environment.abbe_offset_mm = 0.0;
  scale_only.environment.angular_error_range_rad = 0.0;
  scale_only.environment.setup_repeatability_mm = 0.0;
  scale_only.environment.environmental_variation_mm = 0.0;
  scale_only.environment.dead_path_mm = 0.0;
  UncertaintyBudget b;
  addLaserLengthContributors(b, kScaleLengthMm, scale_only);
  return b.contributors.empty() ? 0.0 : b.combinedStandardUncertainty() / kScaleLengthMm;
}

}  // namespace

UncertaintyBudget diagonalLineInputs(std::span<const DiagonalLineInput> lines,
                                     const UncertaintySources& src) {
  std::string why;
  PKM_CHECK(src.isValid(&why), "uncertainty sources: {}", why);
  PKM_CHECK(!lines.empty(), "diagonal uncertainty: no line");
  UncertaintyBudget b;
  b.unit = "rad";
  b.coverage_factor = src.coverage_factor;
  b.contributors.push_back(input("laser scale (wavelength, air sensors, material temperature)",
                                 commonScale(src),
                                 "1",
                                 Distribution::kNormal,
                                 "instrument and environment"));
  const double theta = src.environment.misalignment_rad;
  for (const DiagonalLineInput& line : lines) {
    PKM_CHECK(std::isfinite(line.length_mm) && line.length_mm > 0.0,
              "diagonal uncertainty: line '{}' has length {}",
              line.name,
              line.length_mm);
    PKM_CHECK(std::isfinite(line.statistics_mm) && line.statistics_mm >= 0.0,
              "diagonal uncertainty: line '{}' has statistics {}",
              line.name,
              line.statistics_mm);
    b.contributors.push_back(input(line.name + ": test statistics",
                                   line.statistics_mm,
                                   "mm",
                                   Distribution::kNormal,
                                   "test data"));
    // Two readings, each ±res/2 (rectangular): their difference as one ±res/√2 input (the same
    // variance, res²/6).
    b.contributors.push_back(input(line.name + ": laser resolution (two readings)",
                                   src.laser.resolution_mm / std::sqrt(2.0),
                                   "mm",
                                   Distribution::kRectangular,
                                   "instrument"));
    b.contributors.push_back(input(line.name + ": cosine error",
                                   line.length_mm * theta * theta / 2.0,
                                   "mm",
                                   Distribution::kRectangular,
                                   "set-up"));
  }
  b.conditions = laserConditions(src);
  return b;
}

double lineLengthError(std::span<const double> x, std::size_t line, double length_mm) {
  const std::size_t k = 1 + 3 * line;
  return x[0] * length_mm + x[k] + x[k + 1] + x[k + 2];
}

double bodyDiagonalStatistics(std::span<const BodyDiagonalSample> samples,
                              const BodyDiagonalResult& result,
                              BodyDiagonal diagonal) {
  double sum = 0.0, sum2 = 0.0;
  std::size_t n = 0;
  for (const BodyDiagonalSample& s : samples) {
    if (s.diagonal != diagonal) continue;
    sum += s.position;
    sum2 += s.position * s.position;
    ++n;
  }
  const double sxx = n ? sum2 - sum * sum / static_cast<double>(n) : 0.0;
  if (n < 3 || !(sxx > 0.0)) return 0.0;
  const double rms = result.diagonals[static_cast<std::size_t>(diagonal)].residual_rms;
  const double s = rms * std::sqrt(static_cast<double>(n) / static_cast<double>(n - 2));
  return s / std::sqrt(sxx) * result.length;
}

UncertaintyBudget bodyDiagonalLengthErrorUncertainty(std::span<const BodyDiagonalSample> samples,
                                                     const BodyDiagonalResult& result,
                                                     BodyDiagonal diagonal,
                                                     const UncertaintySources& src) {
  UncertaintyBudget b;
  b.quantity = "length_error";
  b.unit = "mm";
  b.value = result.diagonals[static_cast<std::size_t>(diagonal)].length_error;
  b.coverage_factor = src.coverage_factor;
  addLaserLengthContributors(b, result.length, src);
  addContributor(b,
                 input("least-squares slope x D",
                       bodyDiagonalStatistics(samples, result, diagonal),
                       "mm",
                       Distribution::kNormal,
                       "test data"));
  return b;
}

NonlinearBudget propagateBothWays(const std::string& quantity,
                                  const std::string& unit,
                                  double value,
                                  const MeasurementModel& model,
                                  const UncertaintyBudget& inputs,
                                  const MonteCarloOptions& options) {
  NonlinearBudget out;
  const UncertaintyBudget linear = linearizeModel(model, inputs);
  out.linear.quantity = quantity;
  out.linear.unit = unit;
  out.linear.value = value;
  out.linear.coverage_factor = inputs.coverage_factor;
  out.linear.conditions = inputs.conditions;
  for (const UncertaintyContributor& c : linear.contributors) addContributor(out.linear, c);
  out.monte_carlo = propagateMonteCarlo(model, inputs, options);
  return out;
}

UncertaintyBudget eq11Uncertainty(const UncertaintyBudget& parallelism,
                                  double travel_mm,
                                  int sign,
                                  const std::string& quantity,
                                  double value) {
  PKM_CHECK(std::isfinite(travel_mm) && travel_mm > 0.0,
            "eq. 11 uncertainty: the travel must be finite and > 0, got {}",
            travel_mm);
  PKM_CHECK(sign == 1 || sign == -1, "eq. 11 uncertainty: sign must be +1 or -1, got {}", sign);
  UncertaintyBudget b = parallelism;
  b.quantity = quantity;
  b.unit = "rad";
  b.value = value;
  for (UncertaintyContributor& c : b.contributors) c.sensitivity *= sign / travel_mm;
  return b;
}

}  // namespace pkm::metrology
