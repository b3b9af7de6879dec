/// @file
/// @brief The shifted-diagonal ("moving diagonal") method of Hwang et al. ("Analysis of multi-axis
/// volumetric errors"; J. Hwang, C. B. Bui, J. Shim, Y. J. Kim, C. H. Lee, KIMM): each body
/// diagonal is measured once as it is and once with its end point shifted along each axis; the
/// triangle of the two measured lengths and the commanded shift gives the diagonal's travel along
/// that axis (eqs 1-3), four diagonals give the 9 error components (eq 5) and the squareness angles
/// (eq 6).
#pragma once

#include <array>
#include <span>

#include "pkm/metrology/body_diagonals.hpp"

namespace pkm::metrology {

/// The triangle of Hwang et al. ("Analysis of multi-axis volumetric errors"), eqs (1)-(3): common
/// start O, the diagonal's end A (|OA| = r0), the shifted end B (|OB| = rm), AB along the shifted
/// axis with |AB| = |shift|.
struct ShiftTriangle {
  double delta_alpha = 0.0;  ///< Δα, the angle at O between OA and OB, rad (eq 2)
  double alpha = 0.0;        ///< α, the angle of OA from the plane normal to the axis, rad (eq 3)
  double component = 0.0;    ///< R_real, the travel of OA along the axis, mm (eq 1)
};

/// Hwang et al. ("Analysis of multi-axis volumetric errors"), eqs (1)-(3), as printed, for a shift
/// `shift` (mm, signed: > 0 lengthens the diagonal's travel along the axis, < 0 shortens it):
///   Δα = acos((r0² + rm² − Δ²)/(2·r0·rm)), α = π/2 − asin(rm·sin Δα/|Δ|),
///   R_real = rm·sin(α + σΔα) − σ|Δ| (σ = sign of the shift; eq 1 is the σ = +1 case).
/// Equal to shiftComponent() (law of cosines) up to rounding. Throws pkm::InvalidArgument unless
/// r0, rm > 0, shift ≠ 0, all finite, and the three lengths form a triangle.
[[nodiscard]] ShiftTriangle shiftTriangle(double r0, double rm, double shift);

/// The same travel in closed form: (rm² − r0² − Δ²)/(2Δ) (the projection of OA on the direction
/// of AB, law of cosines). Throws as shiftTriangle for a zero or non-finite shift.
[[nodiscard]] double shiftComponent(double r0, double rm, double shift);

/// One diagonal-length measurement of the procedure.
struct ShiftedDiagonalMeasurement {
  BodyDiagonal diagonal = BodyDiagonal::kPPP;
  int axis = -1;       ///< −1: the diagonal itself; 0, 1, 2: its end shifted along X, Y, Z
  double shift = 0.0;  ///< the commanded displacement of the end point along +axis, mm (≠ 0)
  /// Measured minus nominal length of the (shifted) diagonal from its start, mm.
  double length_error = 0.0;
};

/// The evaluation.
struct ShiftedDiagonalResult {
  /// ΔR per diagonal (kBodyDiagonals order) and axis: the triangulated travel along the axis, in
  /// the diagonal's travel direction, minus the nominal travel L_axis, mm.
  std::array<std::array<double, 3>, 4> travel_errors{};
  /// Eq (5) and its analogues, [j][i] = e_j(i): the error along axis j due to the full travel of
  /// axis i, mm. e_j(j) = (ΔR_j,PPP + ΔR_j,F_j)/2 and e_j(i) = (ΔR_j,PPP − ΔR_j,F_i)/2 (i ≠ j),
  /// F_x = NPP, F_y = PNP, F_z = PPN (the paper's name for NNP traversed backwards).
  std::array<std::array<double, 3>, 3> components{};
  /// Scale error of each axis from e_j(j): triangulating with the commanded shift measures the
  /// metric G = MᵀM (G_jj = 1 + 2k_j), so e_j(j) = k_j·(2L_j + Δ̄_j) with Δ̄_j the mean
  /// along-travel shift of the two diagonals used (first order, linear scale field).
  std::array<double, 3> scale{};
  /// Squareness (project convention, rad: xy, xz, yz) from the components, the reported value:
  /// −(e_i(j)/L_j + e_j(i)/L_i)/2 (G_ij = cos of the included angle). Independent of the scale
  /// estimate, so the least noisy of the three (≈ 0.1-1 µrad with XL-80 noise, Δ = 50 mm).
  std::array<double, 3> squareness{};
  /// Eq (6) as printed, with the nominal R_ideal: biased by the scale errors by −K/(Li·Lj)
  /// (K as in body_diagonals.hpp).
  std::array<double, 3> squareness_eq6{};
  /// Eq (6) with R_ideal² = Σ L_j²(1 + 2k_j) from `scale`: first-order exact with scale errors,
  /// but it inherits the noise of the k_j (≈ 5 µrad with XL-80 noise, Δ = 50 mm).
  std::array<double, 3> squareness_eq6_scaled{};
  /// The asymmetry e_i(j)/L_j − e_j(i)/L_i (≈ 0 when the linear model holds; G is symmetric),
  /// rad, xy, xz, yz.
  std::array<double, 3> asymmetry{};
};

/// Evaluates the procedure on a box `size` (mm). Needs each of the four diagonals unshifted and
/// shifted along X, Y and Z (repeated measurements of one (diagonal, axis) are averaged; they must
/// share the shift). Throws pkm::InvalidArgument for a missing or inconsistent measurement, a shift
/// of zero or one larger than half the axis length, or non-finite values.
[[nodiscard]] ShiftedDiagonalResult evaluateShiftedDiagonals(
    std::span<const ShiftedDiagonalMeasurement> measurements, const Eigen::Vector3d& size);

}  // namespace pkm::metrology
