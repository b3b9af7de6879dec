// Squareness from diagonals, linear and Monte Carlo (metrology/squareness_uncertainty.hpp).
#include "pkm/metrology/squareness_uncertainty.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/metrology/body_diagonals.hpp"
#include "pkm/metrology/profile_uncertainty.hpp"
#include "pkm/metrology/shifted_diagonal.hpp"

namespace pkm::metrology {
namespace PKM_TEST_NS {

constexpr double kTolLinear = 1e-9;       // relative: central differences of a linear model
constexpr double kTolMonteCarlo = 0.02;   // relative: u from 20000 trials (sd of u ≈ 0.5 %)
constexpr double kTolBudget = 1e-15;      // mm, rad: arithmetic of one contributor
constexpr double kTolStatistics = 1e-12;  // mm: a least-squares line, then a square root
const Eigen::Vector3d kBox{500.0, 400.0, 300.0};

/// Sources with only the lines' statistics: no scale, resolution or cosine error.
UncertaintySources statisticsOnly() {
  UncertaintySources s;
  s.laser.wavelength_accuracy_ppm = 0.0;
  s.laser.air_temperature_accuracy_k = 0.0;
  s.laser.air_pressure_accuracy_pa = 0.0;
  s.laser.air_humidity_accuracy_percent = 0.0;
  s.laser.material_temperature_accuracy_k = 0.0;
  s.environment.expansion_coefficient_accuracy_per_k = 0.0;
  s.laser.resolution_mm = 0.0;
  s.environment.misalignment_rad = 0.0;
  return s;
}

TEST(SquarenessUncertainty, InputLayoutAndValues) {
  // Defaults: θ = 50 µrad, so a 700 mm line's cosine error is 700 × (50e-6)²/2 = 8.75e-7 mm;
  // resolution 1 nm as ±1e-6/√2 mm; the statistics as given.
  const std::vector<DiagonalLineInput> lines{{"a", 700.0, 2e-4}, {"b", 500.0, 0.0}};
  const UncertaintyBudget in = diagonalLineInputs(lines, {});
  ASSERT_EQ(in.contributors.size(), 7u);
  EXPECT_GT(in.contributors[0].value, 0.0);  // the common scale
  EXPECT_EQ(in.contributors[0].unit, "1");
  EXPECT_NEAR(in.contributors[1].value, 2e-4, kTolBudget);
  EXPECT_NEAR(in.contributors[2].value, 1e-6 / std::sqrt(2.0), kTolBudget);
  EXPECT_NEAR(in.contributors[3].value, 700.0 * 50e-6 * 50e-6 / 2.0, kTolBudget);
  EXPECT_EQ(in.contributors[6].name, "b: cosine error");
  const std::vector<double> x{1e-6, 1e-3, 2e-3, 3e-3, 4e-3, 5e-3, 6e-3};
  EXPECT_NEAR(lineLengthError(x, 1, 500.0), 500.0 * 1e-6 + 4e-3 + 5e-3 + 6e-3, kTolBudget);
  const std::vector<DiagonalLineInput> bad{{"a", 0.0, 0.0}};
  EXPECT_THROW((void)diagonalLineInputs(bad, {}), InvalidArgument);
  EXPECT_THROW((void)diagonalLineInputs({}, {}), InvalidArgument);
}

TEST(SquarenessUncertainty, BodyDiagonalsByHand) {
  // EC0Y = D(−Δ1 + Δ2 + Δ3 − Δ4)/(4 Lx Ly): four independent ΔD with u = 1 µm give
  // u = D/(4 Lx Ly) · √4 · 1e-3 = 707.107/(4 × 200000) × 2e-3 = 1.76777e-6 rad. A common scale
  // (every ΔD + ε D) cancels: its sensitivity is 0.
  const double D = kBox.norm();
  std::vector<DiagonalLineInput> lines;
  for (BodyDiagonal d : kBodyDiagonals) lines.push_back({toString(d), D, 1e-3});
  const UncertaintyBudget in = diagonalLineInputs(lines, statisticsOnly());
  const MeasurementModel xy = [&](std::span<const double> x) {
    std::array<double, 4> e{};
    for (std::size_t k = 0; k < 4; ++k) e[k] = lineLengthError(x, k, D);
    return solveBodyDiagonals(kBox, e).squareness_xy;
  };
  const NonlinearBudget b = propagateBothWays("squareness_xy", "rad", 0.0, xy, in);
  const double expected = D / (4.0 * 500.0 * 400.0) * 2.0 * 1e-3;
  EXPECT_NEAR(b.linear.combinedStandardUncertainty(), expected, kTolLinear * expected);
  EXPECT_EQ(b.linear.contributors.size(), 4u);  // the zero inputs are dropped
  EXPECT_EQ(b.linear.unit, "rad");
  EXPECT_NEAR(b.monte_carlo.standard_uncertainty, expected, kTolMonteCarlo * expected);
}

TEST(SquarenessUncertainty, ShiftedDiagonalsMonteCarloAgreesWithLinear) {
  // The shifted triangle is non-linear (law of cosines), but µm errors on 700 mm lines keep it
  // near-linear: Monte Carlo and the linear budget must agree on every squareness.
  std::vector<ShiftedDiagonalMeasurement> ms;
  std::vector<DiagonalLineInput> lines;
  for (BodyDiagonal d : kBodyDiagonals) {
    for (int axis = -1; axis < 3; ++axis) {
      const double shift = axis < 0 ? 0.0 : -50.0 * travelSigns(d)[axis];
      ms.push_back({d, axis, shift, 2e-3 * (axis + 2)});
      Eigen::Vector3d travel = diagonalTravel(d, kBox);
      if (axis >= 0) travel[axis] += shift;
      lines.push_back({"line", travel.norm(), 0.5e-3});
    }
  }
  const UncertaintyBudget in = diagonalLineInputs(lines, {});
  const ShiftedDiagonalResult nominal = evaluateShiftedDiagonals(ms, kBox);
  for (std::size_t q = 0; q < 3; ++q) {
    const MeasurementModel model = [&](std::span<const double> x) {
      std::vector<ShiftedDiagonalMeasurement> p = ms;
      for (std::size_t i = 0; i < p.size(); ++i)
        p[i].length_error += lineLengthError(x, i, lines[i].length_mm);
      return evaluateShiftedDiagonals(p, kBox).squareness[q];
    };
    const NonlinearBudget b =
        propagateBothWays("s", "rad", nominal.squareness[q], model, in, {.trials = 20000});
    const double u = b.linear.combinedStandardUncertainty();
    EXPECT_GT(u, 0.0);
    EXPECT_NEAR(b.monte_carlo.standard_uncertainty, u, kTolMonteCarlo * u) << q;
    EXPECT_NEAR(b.monte_carlo.mean, nominal.squareness[q], u / 10.0) << q;
  }
}

TEST(SquarenessUncertainty, BodyDiagonalLengthErrorByHand) {
  // Every diagonal read at 0, D/2, D: deviations 0, 1, 0 µm. Line: slope 0, residuals −1/3, 2/3,
  // −1/3 µm, RMS √(2/9) µm; s = RMS·√(3/1); Σ(u − ū)² = D²/2, so u(ΔD) = s/(D/√2)·D
  // = √(2/9)·√3·√2 µm = √(4/3) µm = 1.1547 µm.
  const double D = kBox.norm();
  std::vector<BodyDiagonalSample> samples;
  for (BodyDiagonal d : kBodyDiagonals)
    for (const auto& [position, deviation] : {std::pair{0.0, 0.0}, {D / 2, 1e-3}, {D, 0.0}})
      samples.push_back({d, position, deviation});
  const BodyDiagonalResult r = evaluateBodyDiagonals(samples, kBox, {.iso230_2 = false});
  const double expected = std::sqrt(4.0 / 3.0) * 1e-3;
  EXPECT_NEAR(bodyDiagonalStatistics(samples, r, BodyDiagonal::kNNP), expected, kTolStatistics);
  const UncertaintyBudget only =
      bodyDiagonalLengthErrorUncertainty(samples, r, BodyDiagonal::kPPP, statisticsOnly());
  EXPECT_NEAR(only.combinedStandardUncertainty(), expected, kTolStatistics);
  // With the default laser, the length contributors over D add to it.
  EXPECT_GT(bodyDiagonalLengthErrorUncertainty(samples, r, BodyDiagonal::kPPP, {})
                .combinedStandardUncertainty(),
            expected);
}

TEST(SquarenessUncertainty, Eq11FromTheParallelismBudget) {
  // Parallelism over a 300 mm travel with U = 1.9 µm: U(sxP) = 1.9e-3/300 rad; szP the same.
  const std::vector<double> u{0, 100, 200, 300};
  const std::vector<double> r{1e-3, -1e-3, -1e-3, 1e-3};
  const UncertaintyBudget p = parallelismUncertainty(0.01, {u, r}, {u, r}, {});
  const UncertaintyBudget sx = eq11Uncertainty(p, 300.0, 1, "sxP", 0.01 / 300.0);
  const UncertaintyBudget sz = eq11Uncertainty(p, 300.0, -1, "szP", -0.002);
  EXPECT_NEAR(sx.expandedUncertainty(), p.expandedUncertainty() / 300.0, kTolBudget);
  EXPECT_NEAR(sz.expandedUncertainty(), p.expandedUncertainty() / 300.0, kTolBudget);
  EXPECT_EQ(sz.unit, "rad");
  EXPECT_EQ(sz.quantity, "szP");
  EXPECT_THROW((void)eq11Uncertainty(p, 0.0, 1, "sxP", 0.0), InvalidArgument);
  EXPECT_THROW((void)eq11Uncertainty(p, 300.0, 2, "sxP", 0.0), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::metrology
