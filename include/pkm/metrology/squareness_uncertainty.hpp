/// @file
/// @brief Uncertainty of squareness from laser diagonal tests (face diagonals, MXT700S parallelism
/// paper, eqs 4-10; ISO 230-6 body diagonals; Hwang et al.'s ("Analysis of multi-axis volumetric
/// errors") shifted diagonals; Wang's step diagonal). The chains from line lengths to squareness
/// are non-linear (least squares, the shifted triangle, the step extraction), so the result is
/// propagated twice: by the law of propagation with sensitivities from linearizeModel (GUM §5.1)
/// and by Monte Carlo (GUM Supplement 1, JCGM 101:2008), ISO/TR 230-9 §6 for the laser
/// contributors. docs/analysis.md, "Budget: squareness from diagonals".
#pragma once

#include <span>
#include <string>
#include <vector>

#include "pkm/metrology/body_diagonals.hpp"
#include "pkm/metrology/monte_carlo.hpp"
#include "pkm/metrology/uncertainty_budget.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"

namespace pkm::metrology {

/// One laser line of a diagonal test, as an input of the squareness model.
struct DiagonalLineInput {
  std::string name;        ///< "PPP", "PPP shifted x", "diagonal 1", ...
  double length_mm = 0.0;  ///< nominal length measured along the line, mm (> 0)
  /// Standard uncertainty of the line's length error from the test's own data (repeated runs,
  /// the least-squares slope's standard error times the length), mm; 0 when the data give none.
  double statistics_mm = 0.0;
};

/// The input budget of a diagonal model (estimates 0, sensitivities 1; linearizeModel sets them):
/// [0] the laser's common scale (relative, "1": vacuum wavelength, air sensors through Edlén,
/// material temperature and expansion coefficient — addLaserLengthContributors over 1 m, as one
/// normal input, the same on every line), then per line three length errors in mm: the data's
/// statistics (normal), the resolution of its two readings (rectangular, ±res/2 each, combined
/// as ±res/√2) and the cosine error L·θ²/2 (rectangular). Contributors that do not apply (zero)
/// are kept so the layout stays fixed. Throws pkm::InvalidArgument for invalid sources, no line,
/// a length that is not finite and > 0 or negative statistics.
[[nodiscard]] UncertaintyBudget diagonalLineInputs(std::span<const DiagonalLineInput> lines,
                                                   const UncertaintySources& sources);

/// The length error (mm) a draw `x` of diagonalLineInputs adds to line `line` of length
/// `length_mm`: x[0]·L + the line's three inputs. Precondition: x has 1 + 3·lines entries.
[[nodiscard]] double lineLengthError(std::span<const double> x, std::size_t line, double length_mm);

/// Standard uncertainty (mm) of the length error ΔD = slope · D of body diagonal `diagonal` from
/// its readings: the least-squares slope's standard error s_r √(n/(n − 2))/√Σ(u − ū)² times D
/// (s_r the residuals' RMS of `result`; they include the diagonal's straightness shape, so this is
/// conservative); 0 with fewer than 3 readings or a single position.
[[nodiscard]] double bodyDiagonalStatistics(std::span<const BodyDiagonalSample> samples,
                                            const BodyDiagonalResult& result,
                                            BodyDiagonal diagonal);

/// Budget "length_error" (mm) of body diagonal `diagonal` (ISO 230-6): the laser's length
/// contributors over D (addLaserLengthContributors) and bodyDiagonalStatistics. Throws
/// pkm::InvalidArgument for invalid sources.
[[nodiscard]] UncertaintyBudget bodyDiagonalLengthErrorUncertainty(
    std::span<const BodyDiagonalSample> samples,
    const BodyDiagonalResult& result,
    BodyDiagonal diagonal,
    const UncertaintySources& sources);

/// A budget propagated both ways.
struct NonlinearBudget {
  UncertaintyBudget linear;      ///< GUM §5.1: sensitivities by central differences
  MonteCarloResult monte_carlo;  ///< GUM Supplement 1 over the same inputs and model
};

/// Propagates `inputs` through `model` (a squareness from perturbed lines, rad) both ways: the
/// linear budget's quantity and unit are `quantity` and `unit`, its value `value` (the reported
/// result; the model's value at the estimates may differ only by rounding) and its coverage factor
/// the inputs'. Contributors with a zero contribution are dropped from the linear budget. Throws
/// as linearizeModel and propagateMonteCarlo.
[[nodiscard]] NonlinearBudget propagateBothWays(const std::string& quantity,
                                                const std::string& unit,
                                                double value,
                                                const MeasurementModel& model,
                                                const UncertaintyBudget& inputs,
                                                const MonteCarloOptions& options = {});

/// Budget of a squareness from the MXT700S parallelism paper, eq. 11 (rad): sxP = Δα (`sign` +1) or
/// szP = szX2 − Δγ (`sign` −1), from the budget of the parallelism Δ·L over the axis travel
/// `travel_mm` (mm, > 0; metrology::parallelismUncertainty): the same contributors with
/// sensitivities sign/travel. The given szX2 carries no uncertainty here (the parallelism command
/// takes it as a number). The chain is linear, so no Monte Carlo. Throws pkm::InvalidArgument for a
/// travel that is not finite and > 0 or a sign other than ±1.
[[nodiscard]] UncertaintyBudget eq11Uncertainty(const UncertaintyBudget& parallelism,
                                                double travel_mm,
                                                int sign,
                                                const std::string& quantity,
                                                double value);

}  // namespace pkm::metrology
