/// @file
/// @brief Wang's step-diagonal ("laser vector") extraction (C. Wang, "Laser vector measurement
/// technique for the determination and compensation of volumetric positioning errors. Part I: Basic
/// theory", Rev. Sci. Instrum. 71(10):3933-3937, 2000): from the readings after each single-axis
/// sub-move along the four body diagonals, the 9 displacement and straightness functions, the three
/// squareness errors from their slopes and the consistency residual Q. Model-based estimates: the
/// additive model (no angular/Abbe coupling) is assumed; Q shows where it fails (Chapman,
/// "Limitations of laser diagonal measurements", Precision Engineering 27(4), 2003).
#pragma once

#include <array>
#include <span>
#include <vector>

#include "pkm/metrology/body_diagonals.hpp"

namespace pkm::metrology {

/// One step of a pass: the machine went to `target` by moving X, then Y, then Z alone, and the
/// laser was read after each sub-move.
struct StepDiagonalStep {
  double target = 0.0;  ///< commanded distance along the diagonal after the step, mm
  /// Deviation (reading minus nominal position along the beam, mm) after the X, Y and Z sub-moves;
  /// the third is at `target`.
  std::array<double, 3> deviation{};
};

/// One pass along a body diagonal, steps in the order taken. The first step only provides the
/// reference (its sub-moves start from outside the target grid, e.g. the overshoot); the targets of
/// the others are the grid. Ascending targets: a + pass; descending: a − pass (its increments are
/// reversed onto the same intervals, exact for the additive model).
struct StepDiagonalPass {
  BodyDiagonal diagonal = BodyDiagonal::kPPP;
  std::vector<StepDiagonalStep> steps;
};

/// The three functions extracted for one moving axis, on a grid of that axis's positions.
struct StepDiagonalAxis {
  std::vector<double> positions;  ///< axis positions, ascending (from the box corner, mm)
  /// The error components along X, Y and Z caused by this axis (for axis X: EXX, EYX, EZX), mm,
  /// referred to 0 at the first position (axis position 0 for targets from 0 to D; Wang 2000).
  std::array<std::vector<double>, 3> components;
  /// Least-squares slopes of the three components over position (rad or ratio).
  std::array<double, 3> slopes{};
  /// Straightness (max − min of the residuals from the least-squares line) of the three; the one
  /// along the axis itself (positioning) is reported the same way.
  std::array<double, 3> straightness{};
  /// Consistency residual Q = R1 − R2 − R3 + R4 at each position, mm (≈ 0 when the model holds).
  std::vector<double> residual;
};

/// The result of the extraction.
struct StepDiagonalResult {
  std::array<StepDiagonalAxis, 3> axes;  ///< X, Y, Z sub-moves
  double squareness_xy = 0.0;            ///< ∠(+X,+Y) − 90°, rad (= EC0Y)
  double squareness_xz = 0.0;            ///< ∠(+X,+Z) − 90°, rad (= −EB0Z)
  double squareness_yz = 0.0;            ///< ∠(+Y,+Z) − 90°, rad (= EA0Z)
  double residual_max = 0.0;             ///< max |Q| over all axes and positions, mm
};

/// Wang's extraction (Wang 2000). Per diagonal k (1 PPP, 2 NPP, 3 PNP, 4 NNP) and axis q,
/// the deviation increments of the q sub-moves are averaged over passes per interval and summed
/// into R_k(q), referred to 0 at axis position 0. Direction cosines a = Lx/D, b = Ly/D, c = Lz/D:
///   E_Xq = (R1 − R2 + R3 − R4)/(4a),  E_Yq = (R1 + R2 − R3 − R4)/(4b),  E_Zq = ΣR/(4c),
///   Q = R1 − R2 − R3 + R4;
/// squareness from the least-squares slopes: EC0Y = −(slope EYX + slope EXY), EB0Z = slope EXZ +
/// slope EZX, EA0Z = −(slope EYZ + slope EZY) (first-order rigid-body model, ISO 230-1 names);
/// reported in the project convention (xy = EC0Y, xz = −EB0Z, yz = EA0Z). One pass per diagonal
/// suffices; the axis grids of the four must coincide (uniform targets from 0 to D give that).
/// Throws pkm::InvalidArgument for a missing diagonal, a pass with fewer than 2 steps, non-finite
/// values, passes of one diagonal on different grids, or grids of the four diagonals that do not
/// coincide within 1e-6 mm.
[[nodiscard]] StepDiagonalResult extractStepDiagonal(std::span<const StepDiagonalPass> passes,
                                                     const Eigen::Vector3d& size);

}  // namespace pkm::metrology
