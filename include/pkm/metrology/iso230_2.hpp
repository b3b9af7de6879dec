/// @file
/// @brief ISO 230-2 evaluation of the accuracy and repeatability of positioning of a single NC
/// axis (ISO 230-2:2014 definitions; the formulas are listed in docs/analysis.md, "ISO 230-2
/// positioning").
#pragma once

#include <span>
#include <vector>

namespace pkm::metrology {

/// One reading of an ISO 230-2 test cycle: the j-th approach to target P_i from one direction.
struct PositioningSample {
  double target = 0.0;    ///< commanded position P_i (any length or angle unit)
  int direction = 1;      ///< approach direction: +1 (positive, "↑") or -1 (negative, "↓")
  int run = 1;            ///< run index j >= 1 (unique per target and direction)
  double measured = 0.0;  ///< actual position P_ij, same unit as target
};

/// Options of evaluateIso230_2.
struct Iso230_2Options {
  /// Coverage factor k of the accuracy and repeatability bands: R_i↑ = 2k s_i↑ and
  /// A = max(x̄ + k s) - min(x̄ - k s). ISO 230-2:1997/2006/2014 use k = 2 (the 1988 edition 3).
  double coverage_factor = 2.0;
};

/// Per-target statistics (ISO 230-2:2014 terms). Deviations x_ij = P_ij - P_i.
/// Quantities of a direction without data, and the bidirectional ones of unidirectional data, are
/// NaN.
struct TargetStatistics {
  double target = 0.0;              ///< P_i
  double mean_up = 0.0;             ///< x̄i↑ mean unidirectional positional deviation
  double mean_down = 0.0;           ///< x̄i↓
  double reversal = 0.0;            ///< B_i = x̄i↑ - x̄i↓ (signed)
  double s_up = 0.0;                ///< s_i↑ estimator of the standard uncertainty, n-1
  double s_down = 0.0;              ///< s_i↓
  double repeatability_up = 0.0;    ///< R_i↑ = 2k s_i↑
  double repeatability_down = 0.0;  ///< R_i↓ = 2k s_i↓
  /// R_i = max(k s_i↑ + k s_i↓ + |B_i|, R_i↑, R_i↓) bidirectional repeatability
  double repeatability = 0.0;
  double mean = 0.0;  ///< x̄i = (x̄i↑ + x̄i↓)/2 mean bidirectional positional deviation
  int runs_up = 0;    ///< number of runs n↑ at this target
  int runs_down = 0;  ///< number of runs n↓ at this target
};

/// Axis results (ISO 230-2:2014 terms). Same unit as the targets. Bidirectional
/// quantities (B, B_mean, R, E, M, A) and those of a missing direction are NaN when `bidirectional`
/// is false.
struct Iso230_2Result {
  std::vector<TargetStatistics> targets;  ///< sorted by ascending target
  double B = 0.0;                         ///< reversal value of the axis: max_i |B_i|
  double B_mean = 0.0;                    ///< mean reversal value: (1/m) Σ B_i (signed)
  double R_up = 0.0;                      ///< unidirectional repeatability max_i R_i↑
  double R_down = 0.0;                    ///< max_i R_i↓
  double R = 0.0;                         ///< bidirectional repeatability max_i R_i
  double E_up = 0.0;    ///< unidirectional systematic positional deviation range of x̄i↑
  double E_down = 0.0;  ///< range of x̄i↓
  double E = 0.0;  ///< bidirectional systematic deviation max(x̄↑,x̄↓) - min(x̄↑,x̄↓)
  double M = 0.0;  ///< range of the mean bidirectional positional deviation x̄i
  double A_up = 0.0;    ///< unidirectional accuracy max(x̄↑ + k s↑) - min(x̄↑ - k s↑)
  double A_down = 0.0;  ///< same for ↓
  double A = 0.0;       ///< bidirectional accuracy over both directions
  bool bidirectional = false;  ///< true when every target has data in both directions
};

/// Evaluates an ISO 230-2 test. Samples may come in any order; the targets are the distinct
/// `target` values (exact equality), any number m >= 1 of them, with any number of runs n >= 2
/// per target and direction (n may differ between targets and directions).
/// Either every target has both directions (bidirectional) or every target has the same single
/// direction (unidirectional: the other direction's and the bidirectional quantities are NaN).
/// @throws pkm::InvalidArgument for an empty input, non-finite values, a direction other than
/// ±1, a run < 1, a duplicate (target, direction, run), fewer than 2 runs for a target-direction,
/// inconsistent direction sets between targets, or coverage_factor <= 0 / non-finite.
[[nodiscard]] Iso230_2Result evaluateIso230_2(std::span<const PositioningSample> samples,
                                              const Iso230_2Options& options = {});

}  // namespace pkm::metrology
