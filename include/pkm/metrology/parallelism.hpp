/// @file
/// @brief Parallelism of an axis to a reference axis from two straightness runs taken with the
/// same beam alignment (MXT700S parallelism paper, §3.1), and the paper's combination of the slope
/// differences with the face-diagonal squareness into the PKM squareness errors (§3.3, eq. 11).
#pragma once

#include <span>
#include <vector>

#include "pkm/metrology/straightness.hpp"

namespace pkm::metrology {

/// One straightness run against the common beam: deviations (any length unit, perpendicular to
/// the beam) at positions of the run's own line coordinate. `beam_sign` (+1 or -1) maps the run's
/// coordinate s to the common beam coordinate u = beam_sign · s (up to an offset), so that two runs
/// whose positive directions are opposite along the beam (MXT700S parallelism paper: +y2 moves the
/// table, so the tool along -y, while +yP moves the tool along +y) are compared along the same
/// beam.
struct BeamRun {
  std::vector<double> positions;   ///< s_k, line coordinate of the run
  std::vector<double> deviations;  ///< d_k, straightness readings (zeroed anywhere)
  int beam_sign = 1;               ///< u = beam_sign · s
};

/// Options of evaluateParallelism.
struct ParallelismOptions {
  /// Representative lines: end point or least squares (MXT700S parallelism paper, §3.1); minimum
  /// zone also works.
  StraightnessReference reference = StraightnessReference::kLeastSquares;
};

/// Parallelism of an axis to a reference axis (MXT700S parallelism paper, §3.1, Fig. 6). Slopes are
/// of deviation against the beam coordinate u (rad for small slopes).
struct ParallelismResult {
  double reference_slope = 0.0;  ///< slope of the reference run's representative line (γY2, αY2)
  double axis_slope = 0.0;       ///< slope of the axis run's representative line (γPy, αPy)
  /// axis_slope - reference_slope: Δγ (horizontal) or Δα (vertical) of §3.1 of the MXT700S
  /// parallelism paper.
  double slope_difference = 0.0;
  /// slope_difference · (u at the axis run's largest s - u at its smallest s): the parallelism
  /// error of the representative lines over the axis travel (signed).
  double parallelism = 0.0;
  /// The parallelism error profile e_k = d_k - line_ref(u_k) - c (the axis readings with the
  /// reference's representative line removed, the MXT700S parallelism paper, §3.1), offset c so
  /// that the axis's own representative line gives e = 0 at its smallest s; input order.
  std::vector<double> deviations;
  double max_deviation = 0.0;  ///< the e_k of largest magnitude (signed), as in Table 3 of the
                               ///< MXT700S parallelism paper
  StraightnessResult reference_straightness;  ///< the reference run about its line
  StraightnessResult axis_straightness;       ///< the axis run about its own line
};

/// Evaluates the parallelism of `axis` to `reference` (MXT700S parallelism paper, §3.1). Throws
/// pkm::InvalidArgument for a beam_sign other than ±1 and as evaluateStraightness for each run.
[[nodiscard]] ParallelismResult evaluateParallelism(const BeamRun& reference,
                                                    const BeamRun& axis,
                                                    const ParallelismOptions& options = {});

/// The PKM squareness errors of §3.3 of the MXT700S parallelism paper in the project convention
/// (docs/conventions.md, "Squareness"), rad.
struct PkmSquareness {
  double sxP = 0.0;  ///< ∠(+y of X2, +PZ) - 90°
  double szP = 0.0;  ///< ∠(+X2, +PY) - 90°
};

/// Eq. 11 and §3.3 of the MXT700S parallelism paper: sxP = Δα and szP from Δγ and szX2 (rad). The
/// PKM's y motion shows an x slope of szX2 - szP against the Y2 line (docs/conventions.md,
/// "Relation to the MXT700S parallelism paper, §3"), so szP = szX2 - Δγ; the printed eq. 11
/// (szP = Δγ - szX2) has the opposite sign from the paper's own numbers (Δγ = 2.81, szX2 = -0.034
/// give its szP = -2.85 mrad), which this follows. Throws pkm::InvalidArgument for non-finite
/// input.
[[nodiscard]] PkmSquareness pkmSquarenessFromSlopes(double dgamma, double dalpha, double szX2);

/// Eq. 11 with the second-order terms, given syP (from the X2-PZ face diagonal). The PKM's y
/// direction in F is Rz(−szX2)·exp([ω_P]×)·ŷ with ω_P = (sxP, −syP, szP) (docs/conventions.md);
/// to second order its x component is szX2 − szP − ½·sxP·syP and its z component
/// sxP − ½·syP·szP, so szP = szX2 − Δγ − ½·sxP·syP and sxP = Δα + ½·syP·szP (solved by two
/// fixed-point passes; the remainder is third order). The MXT700S parallelism paper's
/// sxP·syP/2 = 32 µrad is 10 µm of parallelism over 300 mm. Throws pkm::InvalidArgument for
/// non-finite input.
[[nodiscard]] PkmSquareness pkmSquarenessFromSlopes(double dgamma,
                                                    double dalpha,
                                                    double szX2,
                                                    double syP);

}  // namespace pkm::metrology
