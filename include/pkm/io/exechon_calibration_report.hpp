/// @file
/// @brief The summary of an Exechon calibration (`pkm calibrate exechon`, CAL.summary.json and
/// `--json`; docs/calibration.md): the tripod and wrist fit from PKM tracker files, the hybrid
/// machine's squareness fit from hybrid tracker files, or both, as one typed report and as its JSON
/// document (schema pkm.exechon-calibration-summary/1, documented in docs/formats.md).
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "pkm/calibration/exechon_budget.hpp"
#include "pkm/calibration/exechon_calibration.hpp"
#include "pkm/calibration/exechon_uncertainty.hpp"
#include "pkm/calibration/holdout.hpp"
#include "pkm/calibration/hybrid_calibration.hpp"
#include "pkm/core/units.hpp"

namespace pkm::io {

/// How many distances, and their mean, 95th percentile and maximum (model length unit).
struct DistanceStatistics {
  std::size_t points = 0;
  double mean = 0.0, p95 = 0.0, max = 0.0;
};

/// Held-out errors before (nominal model) and after (calibrated model) a fit.
struct HoldoutComparison {
  calibration::HoldoutErrors before, after;
};

/// The tripod and wrist fit (26 parameters) from the PKM tracker files.
struct ExechonTripodReport {
  std::size_t points = 0, equations = 0;
  Eigen::Vector3d target_offset = Eigen::Vector3d::Zero();  ///< tool frame
  calibration::ExechonCalibrationSummary fit;
  std::array<bool, calibration::kExechonParameters> free{};
  std::optional<HoldoutComparison> holdout;
  /// Over the PKM working box: the tool-point error of the nominal controller on the calibrated
  /// machine, and the linearised tool-point uncertainty the calibration leaves.
  std::optional<DistanceStatistics> map_before, map_after;
  /// --monte-carlo: the spread the calibration leaves and the noise it was simulated with.
  struct MonteCarlo {
    calibration::ExechonMonteCarloSummary summary;
    double sigma_position = 0.0, sigma_orientation = 0.0;
  };
  std::optional<MonteCarlo> monte_carlo;
  /// The uncertainty budgets of the parameters and the predicted tool-point uncertainty
  /// (docs/calibration.md, "Uncertainty budgets").
  struct Uncertainty {
    std::string sources;  ///< the sources file, or "typical datasheet values"
    calibration::ExechonParameterUncertainty parameters;  ///< linear budgets
    /// --uncertainty-trials: the GUM Supplement 1 propagation of the same inputs.
    std::optional<calibration::BudgetMonteCarloResult> monte_carlo;
    std::string tcp_poses;            ///< where the tool-point U is predicted: "held-out"
    calibration::TcpUncertainty tcp;  ///< the predicted tool-point U at those configurations
  };
  std::optional<Uncertainty> uncertainty;
};

/// The uncertainty lines of the text summary (as hexapodCalibrationUncertaintyText); "" without
/// tripod.uncertainty.
[[nodiscard]] std::string exechonCalibrationUncertaintyText(const ExechonTripodReport& tripod,
                                                            LengthUnit unit);

/// The hybrid machine's four squareness errors from the hybrid tracker files.
struct HybridSquarenessReport {
  std::size_t observations = 0;
  std::string known_errors;          ///< the --errors given, or "none"
  bool tripod_error_motion = false;  ///< the calibrated tripod's error motion was included
  calibration::HybridCalibrationSummary fit;
  std::optional<HoldoutComparison> holdout;
  /// The standard uncertainty (rad; szX2, sxP, syP, szP) the calibrated tripod's own uncertainty
  /// gives the squareness through its error motion (its covariance's principal directions, one
  /// re-fit each); zero without a tripod budget. u = √(fit σ² + this²).
  Eigen::Vector4d tripod_standard_uncertainty = Eigen::Vector4d::Zero();
  /// √(fit.standard_deviation² + tripod_standard_uncertainty²), rad.
  [[nodiscard]] Eigen::Vector4d standardUncertainty() const {
    return (fit.standard_deviation.array().square() + tripod_standard_uncertainty.array().square())
        .sqrt();
  }
};

/// An Exechon calibration, as reported.
struct ExechonCalibrationReport {
  std::string machine;
  LengthUnit unit = LengthUnit::kMillimetre;
  std::vector<std::string> data_notes;
  std::optional<ExechonTripodReport> tripod;
  std::optional<HybridSquarenessReport> hybrid;
  std::string out_machine, out_summary, out_errors;  ///< out_errors: "" without hybrid data
};

/// The report as JSON text (two-space indent, closing newline): the exact document
/// `pkm calibrate exechon` writes to CAL.summary.json and prints with --json.
[[nodiscard]] std::string exechonCalibrationJson(const ExechonCalibrationReport& report);

}  // namespace pkm::io
