/// @file
/// @brief The results of `pkm analyze <kind>` as typed reports and as the JSON documents the
/// command prints with --json (docs/analysis.md lists their members; docs/formats.md, "Result
/// documents"). Each report holds the metrology result and what the document also shows (the
/// settings, the points, the counts). The JSON functions return the document's exact text:
/// two-space indent, members in a fixed order, a closing newline, non-finite numbers as null.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "pkm/io/line_numbers.hpp"
#include "pkm/metrology/body_diagonals.hpp"
#include "pkm/metrology/circle_fit.hpp"
#include "pkm/metrology/circular_test.hpp"
#include "pkm/metrology/conformance.hpp"
#include "pkm/metrology/face_diagonal.hpp"
#include "pkm/metrology/iso230_2.hpp"
#include "pkm/metrology/min_zone_circle.hpp"
#include "pkm/metrology/monte_carlo.hpp"
#include "pkm/metrology/parallelism.hpp"
#include "pkm/metrology/plane_prediction.hpp"
#include "pkm/metrology/probe_offset.hpp"
#include "pkm/metrology/shifted_diagonal.hpp"
#include "pkm/metrology/step_diagonal.hpp"
#include "pkm/metrology/straightness.hpp"
#include "pkm/metrology/uncertainty_budget.hpp"

namespace pkm::io {

/// ISO 230-2:2014 positioning accuracy and repeatability of one axis.
struct Iso230_2Report {
  metrology::Iso230_2Result result;
  double coverage = 2.0;  ///< the coverage factor k used
  /// The ISO 230-2 test conditions the data do not meet (metrology::iso230_2Nonconformities);
  /// empty when they conform.
  std::vector<std::string> nonconformities;
  std::vector<std::string> warnings;  ///< plausibility (metrology::implausibleDeviations)
  /// Budgets of E, M, A, B, R (metrology::iso230_2Uncertainty; empty for unidirectional data).
  std::vector<metrology::UncertaintyBudget> uncertainty;
  /// ISO 14253-1 decisions for the tolerances given (none: empty).
  std::vector<metrology::ConformanceResult> conformance;
};

/// Straightness about a reference line (ISO 230-1:2012 §3.4.8).
struct StraightnessReport {
  metrology::StraightnessReference reference = metrology::StraightnessReference::kLeastSquares;
  std::vector<double> position;   ///< the points' positions, input order (length unit)
  std::vector<double> deviation;  ///< their deviations (length unit)
  metrology::StraightnessResult result;
  /// The readings before the per-target mean, when a target was read more than once: their
  /// number and the straightness of all of them about the same kind of line (the raw scatter).
  struct Raw {
    std::size_t points = 0;
    double straightness = 0.0;
  };
  std::optional<Raw> raw;
  /// Budget of the straightness (metrology::straightnessUncertainty).
  std::vector<metrology::UncertaintyBudget> uncertainty;
};

/// The plane of a parallelism measurement (MXT700S parallelism paper, §3.1).
enum class ParallelismPlane {
  kHorizontal,  ///< slope difference Δγ; with szX2 also szP
  kVertical,    ///< slope difference Δα = sxP
};

/// Parallelism of an axis to a reference axis from two straightness runs along one beam
/// (MXT700S parallelism paper, §3.1, eqs 1-3).
struct ParallelismReport {
  ParallelismPlane plane = ParallelismPlane::kHorizontal;
  metrology::StraightnessReference line = metrology::StraightnessReference::kLeastSquares;
  std::vector<double> axis_position;  ///< positions of the axis run (the deviations' abscissa)
  metrology::ParallelismResult result;
  std::optional<double> sxP;  ///< vertical plane: sxP, rad
  std::optional<double> szP;  ///< horizontal plane with szX2 given: szP, rad
  /// Budget of the parallelism (metrology::parallelismUncertainty).
  std::vector<metrology::UncertaintyBudget> uncertainty;
};

/// Face-diagonal squareness (MXT700S parallelism paper, eqs 4-10).
struct SquarenessReport {
  metrology::FaceDiagonalResult result;
  std::size_t diagonals = 0;    ///< diagonals fitted
  std::size_t pdge_tables = 0;  ///< PDGE tables removed
  /// Budget of the squareness (metrology::propagateBothWays: linear, with its Monte Carlo check
  /// in `monte_carlo`, the same order).
  std::vector<metrology::UncertaintyBudget> uncertainty;
  std::vector<metrology::MonteCarloResult> monte_carlo;
};

/// The diagonal method of `pkm analyze diagonals`.
enum class DiagonalMethod {
  kBody,     ///< ISO 230-6:2002 body diagonals
  kShifted,  ///< Hwang et al.'s ("Analysis of multi-axis volumetric errors") shifted diagonals
  kStep,     ///< Wang's step diagonals
};

/// A direct XY measurement compared with the 2-D prediction of a step or shifted analysis.
struct DiagonalComparison {
  std::string file;      ///< the measurement's name (a path or an upload)
  std::string quantity;  ///< "linear" or "straightness"
  metrology::PlaneComparison comparison;
};

/// A diagonal displacement analysis: exactly the result of `method` is set.
struct DiagonalsReport {
  DiagonalMethod method = DiagonalMethod::kBody;
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  ///< the box LX, LY, LZ, mm
  std::optional<metrology::BodyDiagonalResult> body;
  std::optional<metrology::StepDiagonalResult> step;
  std::optional<metrology::ShiftedDiagonalResult> shifted;
  std::vector<DiagonalComparison> compare;  ///< step and shifted only, in input order
  /// Budgets of squareness_xy, _xz, _yz (linear; metrology::propagateBothWays) and their Monte
  /// Carlo propagations in `monte_carlo`, the same order.
  std::vector<metrology::UncertaintyBudget> uncertainty;
  std::vector<metrology::MonteCarloResult> monte_carlo;
};

/// Where a point was read: the input's name and its 1-based line.
struct PointSource {
  std::string name;
  std::size_t line = 0;
};

/// Where each point of a list was read, stored compactly (a name per input, a line per point):
/// a million-point file must not cost a string per point.
class PointSources {
 public:
  /// Starts the points of input `name`: the following addLine calls belong to it.
  void beginInput(std::string name);
  /// Appends a point read at 1-based `line` of the current input. Precondition: beginInput called.
  void addLine(std::size_t line);
  /// Appends points read at `lines` of the current input. Precondition: beginInput called.
  void addLines(const LineNumbers& lines);
  /// Number of points.
  [[nodiscard]] std::size_t size() const { return lines_.size(); }
  /// Input name and line of point `i`. Precondition: i < size().
  [[nodiscard]] PointSource operator[](std::size_t i) const;

 private:
  std::vector<std::string> names_;
  std::vector<std::size_t> first_;  ///< index of the first point of each input
  LineNumbers lines_;
};

/// Least-squares and minimum-zone circles and roundness (ISO 12181-1).
struct CircleReport {
  metrology::CircleFit lsc;
  metrology::MinZoneCircle mzc;
  /// Which of the two the text and JSON report (workflow::CircleRequest::fit).
  bool has_lsc = true, has_mzc = true;
  PointSources sources;  ///< per point, in input order (the contacts' origins)
  /// Budgets of radius, roundness_lsc and roundness_mzc (metrology::circleUncertainty).
  std::vector<metrology::UncertaintyBudget> uncertainty;
};

/// ISO 230-4:2005 circular test.
struct CircularReport {
  metrology::CircularTestResult result;
  std::size_t points_cw = 0, points_ccw = 0;
  /// Budgets of G_cw, G_ccw, G_bidirectional, H and, with a nominal radius, F_max_cw, F_min_cw,
  /// F_max_ccw, F_min_ccw (metrology::circularTestUncertainty).
  std::vector<metrology::UncertaintyBudget> uncertainty;
};

/// Lee et al. (2019), eqs. 8 and 9 averaged over the runs with all six labelled touches.
struct PaperProbeOffset {
  Eigen::Vector2d eq9 = Eigen::Vector2d::Zero();  ///< o_probe by eq. 9, mm
  Eigen::Vector2d eq8 = Eigen::Vector2d::Zero();  ///< o_probe by eq. 8, mm
  int runs = 0;
};

/// Touch-probe stylus offset from master-ring touches (Lee et al. 2019).
struct ProbeOffsetReport {
  metrology::ProbeOffsetFit fit;
  std::size_t touches = 0;
  bool tool_plus_z = false;                       ///< tool direction +z (else −z)
  std::optional<double> effective_stylus_radius;  ///< with a ring diameter, mm
  std::optional<PaperProbeOffset> paper;          ///< with a ring diameter and labelled touches
  /// Budgets of offset_x and offset_y (metrology::probeOffsetUncertainty).
  std::vector<metrology::UncertaintyBudget> uncertainty;
};

/// The JSON documents of `pkm analyze <kind> --json`, one per report type.
[[nodiscard]] std::string analysisJson(const Iso230_2Report& report);
[[nodiscard]] std::string analysisJson(const StraightnessReport& report);
[[nodiscard]] std::string analysisJson(const ParallelismReport& report);
[[nodiscard]] std::string analysisJson(const SquarenessReport& report);
[[nodiscard]] std::string analysisJson(const DiagonalsReport& report);
[[nodiscard]] std::string analysisJson(const CircleReport& report);
[[nodiscard]] std::string analysisJson(const CircularReport& report);
[[nodiscard]] std::string analysisJson(const ProbeOffsetReport& report);

/// "horizontal" or "vertical".
[[nodiscard]] const char* toString(ParallelismPlane plane);
/// "body", "shifted" or "step".
[[nodiscard]] const char* toString(DiagonalMethod method);
/// "lsc", "mzc" or "nominal" (the --centre words of `pkm analyze circular`).
[[nodiscard]] const char* centreName(metrology::CircularCentre centre);

}  // namespace pkm::io
