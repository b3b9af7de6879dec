/// @file
/// @brief `pkm analyze diagonals` as a workflow (docs/analysis.md, "Diagonal methods"): ISO 230-6
/// body diagonals, Hwang et al.'s ("Analysis of multi-axis volumetric errors") shifted diagonals
/// and Wang's step diagonals, with the 2-D XY prediction of the step and shifted methods compared
/// against direct measurements. Inputs come from memory (io::NamedText); every input error is
/// pkm::IoError "NAME:LINE: message".
#pragma once

#include <Eigen/Core>
#include <vector>

#include "pkm/io/analysis_report.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/metrology/monte_carlo.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"
#include "pkm/workflow/progress.hpp"

namespace pkm::workflow {

/// A diagonal displacement analysis.
struct DiagonalsRequest {
  /// Measurement files (`pkm simulate` line files along the diagonals) or tables: body
  /// `diagonal,position,deviation[,run,direction]`, step `...,sub_step,...`, shifted
  /// `diagonal,shift_axis,shift,length_error`. Required.
  std::vector<io::NamedText> data;
  io::DiagonalMethod method = io::DiagonalMethod::kBody;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  ///< the box LX, LY, LZ, mm, each > 0
  double coverage = 2.0;  ///< ISO 230-2 coverage factor k of the body diagonals' statistics
  /// Linear or straightness measurement files of XY lines compared with the 2-D prediction
  /// (step and shifted only).
  std::vector<io::NamedText> compare;
  /// Instruments and environment of the squareness budgets (metrology::diagonalLineInputs).
  metrology::UncertaintySources uncertainty{};
  /// The Monte Carlo propagation beside the linear budgets (each trial re-evaluates the method).
  metrology::MonteCarloOptions monte_carlo{.trials = 20000};
  /// Throws pkm::IoError without data, pkm::InvalidArgument for a box side not finite and > 0 or
  /// comparison files with the body method.
  void validate() const;
};

/// Validates, reads the inputs and evaluates the method. Body diagonals with fewer than 2 runs per
/// target and direction get no ISO 230-2 statistics (a notice says so). Throws as validate(),
/// pkm::IoError for a bad input (a line that is not a body diagonal, a bad sub-step order, ...),
/// pkm::InvalidArgument for data the method cannot use.
[[nodiscard]] io::DiagonalsReport analyzeDiagonals(const DiagonalsRequest& request,
                                                   const RunControl& control = {});

}  // namespace pkm::workflow
