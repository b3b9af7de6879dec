/// @file
/// @brief `pkm analyze iso230-2 | straightness | parallelism | squareness` as workflows
/// (docs/analysis.md, "Positioning"): ISO 230-2 positioning, straightness about a reference line,
/// parallelism from two straightness runs along one beam and face-diagonal squareness (MXT700S
/// parallelism paper, §3). Inputs come from memory (io::NamedText: a file read by the front end or
/// an upload); every input error is pkm::IoError "NAME:LINE: message".
#pragma once

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "pkm/io/analysis_report.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/io/positioning_files.hpp"
#include "pkm/metrology/monte_carlo.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"

namespace pkm::workflow {

/// ISO 230-2:2014 positioning of one axis.
struct Iso230_2Request {
  /// Positioning exports, canonical tables or simulator linear files, concatenated (required;
  /// io::readPositioningSamples).
  std::vector<io::NamedText> data;
  io::PositioningColumns columns;  ///< column assignments and units the headers do not give
  double coverage = 2.0;           ///< coverage factor k (ISO 230-2:2014: 2), > 0
  /// The machine the axis belongs to (a machine file, `.hal` or built-in name; "" : none) or its
  /// LinuxCNC INI ([TRAJ] LINEAR_UNITS): files without a stated unit on an inch machine are
  /// flagged (workflow::unitMismatchWarnings).
  std::string machine;
  std::string ini;  ///< see `machine`
  /// Refuse (pkm::InvalidArgument) data that miss the ISO 230-2 test conditions or look
  /// implausible, instead of flagging them in the report.
  bool strict = false;
  /// The laser and environment of the budgets of E, M, A, B, R (metrology::iso230_2Uncertainty).
  metrology::UncertaintySources uncertainty{};
  /// Tolerances (quantity E, M, A, B or R; upper limit in mm) decided per ISO 14253-1.
  std::vector<std::pair<std::string, double>> tolerances{};
  /// Throws pkm::IoError without data, pkm::InvalidArgument for a coverage factor not > 0.
  void validate() const;
};

/// Validates, reads the samples (io::readPositioningSamples), evaluates ISO 230-2 and checks the
/// test conditions and plausibility (metrology/iso230_2_conformity.hpp). Throws as validate(),
/// pkm::IoError "NAME:LINE: message" for a bad input, pkm::InvalidArgument when the data do not
/// allow the statistics (metrology::evaluateIso230_2) or, with `strict`, do not conform.
[[nodiscard]] io::Iso230_2Report analyzeIso230_2(const Iso230_2Request& request);

/// Straightness about a reference line (ISO 230-1:2012 §3.4.8).
struct StraightnessRequest {
  /// `position,deviation` tables or simulator straightness files (averaged per target; required).
  std::vector<io::NamedText> data;
  metrology::StraightnessReference reference = metrology::StraightnessReference::kLeastSquares;
  /// The straightness optics of the budget (metrology::straightnessUncertainty).
  metrology::UncertaintySources uncertainty{};
  /// Throws pkm::IoError without data.
  void validate() const;
};

/// Validates, reads the profile (io::readStraightness) and evaluates it about the reference line.
/// Throws as validate(), pkm::IoError for a bad input, pkm::InvalidArgument for too few points.
[[nodiscard]] io::StraightnessReport analyzeStraightness(const StraightnessRequest& request);

/// Parallelism of an axis to a reference axis from two straightness runs along one beam (MXT700S
/// parallelism paper, §3.1, eqs 1-3; Δγ, or Δα = sxP in the vertical plane).
struct ParallelismRequest {
  std::vector<io::NamedText> reference;  ///< straightness files of the reference axis (required)
  std::vector<io::NamedText> axis;       ///< straightness files of the axis (required)
  int reference_sign = 1;  ///< +1 or −1: the reference run's positions along or against the beam
  int axis_sign = 1;       ///< +1 or −1, as reference_sign for the axis run
  metrology::StraightnessReference line = metrology::StraightnessReference::kLeastSquares;
  io::ParallelismPlane plane = io::ParallelismPlane::kHorizontal;
  std::optional<double> szX2;  ///< rad; horizontal plane: also report szP (MXT700S parallelism
                               ///< paper, eq 3)
  /// The straightness optics of the budget (metrology::parallelismUncertainty; none when a run
  /// has fewer than 3 points).
  metrology::UncertaintySources uncertainty{};
  /// Throws pkm::IoError without reference or axis data, pkm::InvalidArgument for a sign not
  /// ±1.
  void validate() const;
};

/// Validates, reads both runs and evaluates the parallelism. Throws as validate(), pkm::IoError
/// for a bad input, pkm::InvalidArgument for unusable runs (metrology::evaluateParallelism).
[[nodiscard]] io::ParallelismReport analyzeParallelism(const ParallelismRequest& request);

/// A measured PDGE table for the squareness fit: over the position of axis `argument`,
/// displacing along axis `component` (0: the first axis u, 1: the second axis v).
struct PdgeInput {
  int argument = 0;
  int component = 0;
  /// `position,deviation`, or a simulator linear or straightness file of one moving axis.
  io::NamedText table;
};

/// Face-diagonal squareness (MXT700S parallelism paper, eqs 4-10).
struct SquarenessRequest {
  /// One input per diagonal: `u,v,deviation` tables, or simulator diagonal files (grouped by
  /// their `# measurement`, runs averaged per target). Required.
  std::vector<io::NamedText> data;
  /// Axis positions (first, second) at the start of each u,v diagonal, in data order (missing:
  /// 0, 0); used to look up the PDGE tables.
  std::vector<std::array<double, 2>> start;
  std::vector<PdgeInput> pdge;     ///< PDGE tables removed before the fit
  std::vector<std::string> axes;   ///< the two moving axes of simulator files by name (or none)
  bool fit_scale = false;          ///< also fit the scale errors (needs two diagonals)
  bool first_moves_work = false;   ///< the first axis moves the work, not the tool
  bool second_moves_work = false;  ///< the second axis moves the work (MXT700S parallelism
                                   ///< paper: Y2)
  /// Instruments and environment of the squareness budget (metrology::diagonalLineInputs).
  metrology::UncertaintySources uncertainty{};
  /// The Monte Carlo propagation beside the linear budget (each trial refits the diagonals).
  metrology::MonteCarloOptions monte_carlo{.trials = 20000};
  /// Throws pkm::IoError without data, pkm::InvalidArgument for a PDGE axis not 0 or 1 or a
  /// non-finite start.
  void validate() const;
};

/// Validates, reads the diagonals and PDGE tables and fits the squareness
/// (metrology::fitFaceDiagonalSquareness). Throws as validate(), pkm::IoError "NAME:LINE:
/// message" for a bad input or metadata, pkm::InvalidArgument for an unusable fit.
[[nodiscard]] io::SquarenessReport analyzeSquareness(const SquarenessRequest& request);

}  // namespace pkm::workflow
