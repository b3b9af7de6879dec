/// @file
/// @brief Internal: the squareness budgets of `pkm analyze diagonals` and `pkm analyze squareness`
/// (metrology/squareness_uncertainty.hpp): each method's model from perturbed line lengths,
/// propagated linearly and by Monte Carlo. docs/analysis.md, "Budget: squareness from diagonals".
#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

#include "pkm/metrology/body_diagonals.hpp"
#include "pkm/metrology/face_diagonal.hpp"
#include "pkm/metrology/monte_carlo.hpp"
#include "pkm/metrology/shifted_diagonal.hpp"
#include "pkm/metrology/squareness_uncertainty.hpp"
#include "pkm/metrology/step_diagonal.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"

namespace pkm::workflow::detail {

/// The budgets of squareness_xy, _xz, _yz (rad) and their Monte Carlo propagations.
struct SquarenessBudgets {
  std::vector<metrology::UncertaintyBudget> linear;
  std::vector<metrology::MonteCarloResult> monte_carlo;
};

/// Body diagonals: each diagonal's length error ΔD perturbed; the statistics are the
/// least-squares slope's standard error times D (from the samples about their line).
[[nodiscard]] SquarenessBudgets bodySquarenessBudgets(
    std::span<const metrology::BodyDiagonalSample> samples,
    const metrology::BodyDiagonalResult& result,
    const Eigen::Vector3d& size,
    const metrology::UncertaintySources& sources,
    const metrology::MonteCarloOptions& options);

/// Shifted diagonals: each of the 16 lines' length error perturbed (all repeats of a line alike);
/// the statistics are the pooled scatter of repeated measurements of a line over √n (0 without
/// repeats).
[[nodiscard]] SquarenessBudgets shiftedSquarenessBudgets(
    std::span<const metrology::ShiftedDiagonalMeasurement> measurements,
    const metrology::ShiftedDiagonalResult& result,
    const Eigen::Vector3d& size,
    const metrology::UncertaintySources& sources,
    const metrology::MonteCarloOptions& options);

/// Step diagonals: each diagonal's readings perturbed in proportion to the beam position after
/// every sub-move; the statistics are RMS(Q)/2 (Q = R1 − R2 − R3 + R4 of four independent sums
/// has 4 times the variance of one); and every reading by its own noise, σ = √(reading_noise² +
/// resolution²/12) of the laser (the extraction sums the increments: a random walk), reported as
/// one row "laser reading noise (N readings, ...)".
[[nodiscard]] SquarenessBudgets stepSquarenessBudgets(
    std::span<const metrology::StepDiagonalPass> passes,
    const metrology::StepDiagonalResult& result,
    const Eigen::Vector3d& size,
    const metrology::UncertaintySources& sources,
    const metrology::MonteCarloOptions& options);

/// Face diagonals: each diagonal's deviations perturbed in proportion to s; the statistics are
/// the residuals' standard deviation over √Σs² (the slope through the start) times the length.
[[nodiscard]] SquarenessBudgets faceSquarenessBudget(
    std::span<const metrology::FaceDiagonal> diagonals,
    std::span<const metrology::PdgeTerm> pdge,
    const metrology::FaceDiagonalOptions& fit,
    const metrology::FaceDiagonalResult& result,
    const metrology::UncertaintySources& sources,
    const metrology::MonteCarloOptions& options);

}  // namespace pkm::workflow::detail
