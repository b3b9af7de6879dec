/// @file
/// @brief Squareness of two linear axes from face-diagonal displacement measurements by least
/// squares, after removing the measured position-dependent geometric errors (PDGEs) (MXT700S
/// parallelism paper, §3.2, eqs 4-10; docs/conventions.md, "First-order diagonal formula"),
/// optionally with the two axes' scale errors.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <vector>

#include "pkm/geometry/error_table.hpp"

namespace pkm::metrology {

/// One reading along a face diagonal of the plane of axes a (first) and b (second).
struct DiagonalPoint {
  double u = 0.0;          ///< commanded displacement of axis a from the diagonal's start (signed)
  double v = 0.0;          ///< commanded displacement of axis b from the diagonal's start (signed)
  double deviation = 0.0;  ///< measured minus commanded displacement along the diagonal
};

/// One face diagonal: its readings (the laser zeroed at the start, u = v = 0) and the absolute
/// axis positions of its start, at which the PDGE tables are evaluated.
struct FaceDiagonal {
  std::vector<DiagonalPoint> points;
  double start_a = 0.0;  ///< position of axis a at the start
  double start_b = 0.0;  ///< position of axis b at the start
};

/// A measured PDGE: a one-column table over the position of one axis whose value displaces the
/// tool (relative to the work) along axis a or b by value × (lever + lever_per_other · position of
/// the other axis). Positioning error of a: (argument a, along a, lever 1); straightness of a along
/// b: (a, b, 1); an angular error of a (rad) with an Abbe arm: lever = arm at the other axis's
/// position 0, lever_per_other = ±1 when the arm grows with the other axis (MXT700S parallelism
/// paper: the pitch εyX2 times the PKM z travel in the X2-PZ diagonal).
struct PdgeTerm {
  geometry::ErrorTable1d table;  ///< 1 column: deviation (length) or angle (rad) vs position
  int argument = 0;              ///< 0: evaluated at the position of axis a, 1: of axis b
  int component = 0;             ///< 0: displaces along a, 1: along b
  double lever = 1.0;            ///< factor at the other axis's position 0
  double lever_per_other = 0.0;  ///< added factor per unit position of the other axis
};

/// Options of fitFaceDiagonalSquareness.
struct FaceDiagonalOptions {
  /// Also fit the scale errors k_a, k_b (deviation per unit travel of each axis). Needs
  /// diagonals of two different aspect ratios |u|:|v|; with one aspect ratio (the usual pair of
  /// diagonals of one rectangle) only k_a u² + k_b v² is observable, and a common scale
  /// k = k_a = k_b is fitted instead (FaceDiagonalResult::scale_per_axis = false).
  bool fit_scale = false;
  /// Axis a (first) or b (second) moves the work instead of the tool (MXT700S parallelism paper: Y2
  /// carries the table): the commanded displacement then moves the tool the opposite way, and the
  /// fitted squareness of the relative motions is negated to give the included angle of the axes.
  bool first_moves_work = false;
  bool second_moves_work = false;  ///< see first_moves_work
};

/// The least-squares squareness (MXT700S parallelism paper, eqs 7-8 / 10).
struct FaceDiagonalResult {
  /// Included angle between the positive directions of axes a and b minus 90°, rad (the project
  /// convention; ISO 230-1 EC0Y = +squareness for a = X, b = Y).
  double squareness = 0.0;
  std::optional<std::array<double, 2>> scale;  ///< (k_a, k_b) when fitted, per unit travel
  bool scale_per_axis = false;                 ///< k_a and k_b fitted separately
  double residual_rms = 0.0;                   ///< RMS of the fit residuals, deviation unit
  std::vector<std::vector<double>> residuals;  ///< per diagonal, per point (0 at u = v = 0)
  std::vector<std::vector<double>> corrected;  ///< deviations after removing the PDGEs
  int points_used = 0;                         ///< readings with u² + v² > 0
};

/// Fits the squareness of axes a and b to face-diagonal displacements. First-order model (MXT700S
/// parallelism paper, eq. 6, linearised diagonal length; docs/conventions.md "First-order diagonal
/// formula"): with s = √(u² + v²) and Δa, Δb the PDGE displacements relative to the start,
///   s · deviation = u Δa + v Δb - σ u (v + Δb_b) + k_a u² + k_b v²,
/// solved for σ (and k) by least squares on the residual in deviation units (eqs 7-8). Δb_b, the
/// positioning terms of axis b (argument b, along b), enter the squareness term because the
/// squareness tilts b's actual travel (a second-order refinement; the MXT700S parallelism paper's
/// 0.8 mm PZ error over 210 mm is 0.4 % of syP).
/// @throws pkm::InvalidArgument for no diagonal, non-finite values, a PDGE term with an argument or
/// component outside {0, 1} or a table without exactly one column, fewer readings with s > 0 than
/// unknowns + 1, no reading with u v ≠ 0, or fit_scale with a single diagonal direction.
[[nodiscard]] FaceDiagonalResult fitFaceDiagonalSquareness(std::span<const FaceDiagonal> diagonals,
                                                           std::span<const PdgeTerm> pdge = {},
                                                           const FaceDiagonalOptions& options = {});

}  // namespace pkm::metrology
