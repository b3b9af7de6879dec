/// @file
/// @brief Uncertainty budgets of the ISO 230-4:2005 circular-test results (circular deviation G
/// per run, bidirectional G(b), hysteresis H, radial deviations F), built the way ISO/TR
/// 230-9:2005 §6 builds budgets: the ballbar per its specification (sensor accuracy,
/// resolution, calibrated length), the test's own non-repeatable noise estimated from the data,
/// the least-squares centre's uncertainty through its first-order effect on G, and the bar's
/// temperature. docs/analysis.md, "Budget: ISO 230-4 circular test" lists every contributor.
#pragma once

#include <span>
#include <vector>

#include "pkm/metrology/circle_fit.hpp"
#include "pkm/metrology/circular_test.hpp"
#include "pkm/metrology/uncertainty_budget.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"

namespace pkm::metrology {

/// The standard deviation of the non-repeatable part of a sequence read in order, from its
/// successive differences (von Neumann's mean square successive difference): s² = Σ (d_{k+1} −
/// d_k − d̄)² / (2 (N − 2)), d_k = v_{k+1} − v_k, d̄ their mean. A smooth profile sampled densely
/// (a machine's circular form) contributes its curvature only, the noise fully. 0 for fewer than
/// 3 values.
[[nodiscard]] double successiveDifferenceSigma(std::span<const double> values);

/// Budgets (mm) of `result`, the evaluation of the runs `cw` and `ccw` (in the order measured):
/// "G_cw", "G_ccw", "G_bidirectional", "H" and, when the result has radial deviations (a nominal
/// radius), "F_max_cw", "F_min_cw", "F_max_ccw", "F_min_ccw". Throws pkm::InvalidArgument for
/// invalid sources or fewer than 4 points in a run.
[[nodiscard]] std::vector<UncertaintyBudget> circularTestUncertainty(
    std::span<const Point2> cw,
    std::span<const Point2> ccw,
    const CircularTestResult& result,
    const UncertaintySources& sources);

}  // namespace pkm::metrology
