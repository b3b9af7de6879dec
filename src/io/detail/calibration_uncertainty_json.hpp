/// @file
/// @brief Internal: the "uncertainty" member of the calibration summaries (calibration_report.cpp,
/// exechon_calibration_report.cpp; docs/formats.md, "Calibration uncertainty").
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "pkm/calibration/hexapod_budget.hpp"
#include "pkm/calibration/parameter_budget.hpp"

namespace pkm::io::detail {

/// What a calibration's uncertainty member shows.
struct CalibrationUncertaintyView {
  const std::string& sources;                              ///< where the sources came from
  const calibration::ParameterUncertainty& linear;         ///< the linear budgets
  const calibration::BudgetMonteCarloResult* monte_carlo;  ///< nullptr: none
  const std::string& tcp_poses;                            ///< "held-out" or "workspace"
  const calibration::TcpUncertainty& tcp;                  ///< the predicted TCP U
  const std::string& unit;                                 ///< the machine's length unit
  /// How many budgets, from the first, the text lists (the machine's parameters; the frame and
  /// backlash unknowns after them are in the JSON only).
  std::size_t text_budgets = 0;
};

/// The view of a calibration report's uncertainty (HexapodCalibrationReport::Uncertainty or
/// ExechonTripodReport::Uncertainty: sources, parameters, monte_carlo, tcp_poses, tcp). The text
/// lists the budgets of the parameters that were fitted (parameter index >= 0).
template <typename Uncertainty>
CalibrationUncertaintyView uncertaintyViewOf(const Uncertainty& u, const std::string& unit) {
  std::size_t parameters = 0;
  for (const int k : u.parameters.parameter_indices) parameters += k >= 0 ? 1 : 0;
  return {u.sources,
          u.parameters.linear,
          u.monte_carlo ? &*u.monte_carlo : nullptr,
          u.tcp_poses,
          u.tcp,
          unit,
          parameters};
}

/// {"coverage_factor", "sources", "residual_sigma", "instrument_sigma", "fit_sigma",
/// "parameters": {NAME: budget (with "monte_carlo")}, "monte_carlo": {trials, failures, batches,
/// stabilised, seconds, rule}, "tcp": {"poses", "count", "unit", "U_max", "U_mean", "U"}}.
nlohmann::ordered_json calibrationUncertaintyJson(const CalibrationUncertaintyView& view);

/// The text lines: "calibrated parameters (k = K): value ± U UNIT, largest contributor", one line
/// per budget, the full budget of the one with the largest U, the Monte Carlo line and the
/// predicted TCP uncertainty line.
std::string calibrationUncertaintyText(const CalibrationUncertaintyView& view);

}  // namespace pkm::io::detail
