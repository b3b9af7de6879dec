/// @file
/// @brief Touch-probe stylus offset from touches on a master ring with spindle reversal
/// (Lee et al. 2019, sec. 3.2, eqs. 8-9; H. H. Lee, D. M. Lee, S. H. Yang, JKSPE 36(5):463-469),
/// its least-squares generalisation to any set of spindle angles, the effective stylus radius
/// (ring-gauge calibration of the stylus: touch probe + master ring) and the correction of
/// touches by the offset rotated with the tool (Lee et al. 2019, sec. 3.3).
///
/// Conventions. All vectors lie in the measurement plane (x, y of the machine). A touch records
/// the spindle-axis position s (the tool point with zero probe offset) when the probe triggers.
/// The stylus offset d is the vector from the spindle axis to the stylus-ball centre when the tool
/// is turned by 0 about its axis; turned by ψ (counter-clockwise in the plane) the ball centre is
/// b = s + Rot(ψ)·d. ψ is the spindle angle plus, on an Exechon, the dependent rotation φ_DRM.
/// Eq. 8 of Lee et al. (2019) is written for o_probe = −d (the vector from the ball centre to the
/// spindle axis): probeOffsetEq9 returns the paper's o_probe as printed.
#pragma once

#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

#include "pkm/metrology/circle_fit.hpp"

namespace pkm::metrology {

/// Lee et al. (2019), eq. 9 (small-angle form of eq. 8): o_x = (−x2 + x1 + R_master − r_stylus)/2,
/// o_y = (−y3 + y1 + R_master − r_stylus)/2. (x1, y1): spindle position with the ball centred in
/// the ring at spindle 0°; x2: the +X touch and y3: the +Y touch, both with the spindle reversed
/// (180°). Returns o_probe = −d (mm). Throws pkm::InvalidArgument for non-finite input or r >= R.
[[nodiscard]] Eigen::Vector2d probeOffsetEq9(
    double x1, double y1, double x2, double y3, double ring_radius, double stylus_radius);

/// Lee et al. (2019), eq. 8 solved for o_probe (see probeOffsetEq8) and how the iteration ended.
struct ProbeOffsetEq8Solution {
  Eigen::Vector2d o_probe = Eigen::Vector2d::Zero();  ///< o_probe = −d, mm
  int iterations = 0;                                 ///< Newton steps taken
  bool converged = false;  ///< a step reached the rounding floor of ρ before the step limit
};

/// Lee et al. (2019), eq. 8 by Newton's method from eq. 9, stopped when a step is within the
/// rounding floor of the equations' ρ-sized terms (≤ 8ε·ρ): a few steps for any offset that fits in
/// the ring. Throws pkm::InvalidArgument like probeOffsetEq9 or when the offset does not fit in the
/// ring.
[[nodiscard]] ProbeOffsetEq8Solution solveProbeOffsetEq8(
    double x1, double y1, double x2, double y3, double ring_radius, double stylus_radius);

/// Lee et al. (2019), eq. 8 solved without the small-angle approximation:
/// x2 − x1 = ρ cos θ2 − 2 o_x with sin θ2 = 2 o_y/ρ (the +X touch keeps y = y1),
/// y3 − y1 = ρ sin θ3 − 2 o_y with cos θ3 = 2 o_x/ρ, ρ = R_master − r_stylus; solveProbeOffsetEq8's
/// o_probe. Same arguments and result as probeOffsetEq9; also throws pkm::InvalidArgument when the
/// iteration does not converge.
[[nodiscard]] Eigen::Vector2d probeOffsetEq8(
    double x1, double y1, double x2, double y3, double ring_radius, double stylus_radius);

/// One touch: the spindle-axis position at the trigger and the tool's turn ψ about its axis.
struct ProbeTouch {
  double angle = 0.0;                ///< ψ, rad (spindle angle + DRM), counter-clockwise
  Point2 position = Point2::Zero();  ///< spindle-axis position s at the trigger
};

/// The ball centre b = s + Rot(ψ)·d of a touch (see the file comment).
[[nodiscard]] Point2 ballCentre(const ProbeTouch& touch, const Eigen::Vector2d& offset);

/// Result of fitProbeOffset.
struct ProbeOffsetFit {
  Point2 ring_center = Point2::Zero();               ///< centre of the ring
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();  ///< d, spindle axis -> ball at ψ = 0
  double ball_path_radius = 0.0;  ///< ρ: radius of the ball-centre circle (inside ring: R − r)
  std::vector<double> residuals;  ///< |b_k − centre| − ρ per touch
  double rms = 0.0;               ///< sqrt(mean residual²)
  int iterations = 0;             ///< Gauss-Newton iterations (steps taken)
  bool converged = false;         ///< a convergence criterion was met within max_iterations
};

/// Stopping rules of fitProbeOffset. As the circle fit (CircleFitOptions), every criterion is
/// reachable on noisy touches: a small step, a small relative change of the cost, or a change
/// within the rounding floor N·ε of the cost's sum of N squares.
struct ProbeOffsetOptions {
  int max_iterations = 100;  ///< Gauss-Newton iterations, >= 1
  /// Converged when a step (centre, offset, radius) is below step_tolerance × max(1, ρ).
  double step_tolerance = 1e-10;
  /// Converged when a step changes Σe² by less than cost_tolerance × Σe².
  double cost_tolerance = 1e-12;

  /// True when every field is usable; otherwise false with the reason in *why (if given).
  [[nodiscard]] bool isValid(std::string* why = nullptr) const;
};

/// Least-squares ring centre c, offset d and ball-path radius ρ from touches inside a ring:
/// minimises Σ(|s_k + Rot(ψ_k)·d − c| − ρ)² by Gauss-Newton (start: d = 0, the LSC of the
/// positions; `converged` false only when max_iterations ran out). Needs >= 5 touches at >= 2
/// distinct angles ψ spread around the ring. Throws pkm::InvalidArgument for too few touches,
/// non-finite values, a single angle, a singular problem (c and d not separable) or invalid
/// options.
[[nodiscard]] ProbeOffsetFit fitProbeOffset(std::span<const ProbeTouch> touches,
                                            const ProbeOffsetOptions& options = {});

/// Effective stylus-ball radius from a ring of certified diameter D (ring-gauge calibration:
/// d_eff = D_cert − D_c for an internal ring): D/2 − ρ. Throws pkm::InvalidArgument unless D > 0.
[[nodiscard]] double effectiveStylusRadius(double ring_diameter, double ball_path_radius);

/// Lee et al. (2019), sec. 3.3: the measured surface points of touches on an internal circle, the
/// ball centre b_k = s_k + Rot(ψ_k)·d pushed out by the stylus radius along the approach direction
/// u_k = (b_k − nominal_center)/|b_k − nominal_center|. With ψ_k the true turn of the tool this is
/// the DRM-corrected measurement; with ψ_k = 0 the uncorrected one.
[[nodiscard]] std::vector<Point2> correctedSurfacePoints(std::span<const ProbeTouch> touches,
                                                         const Eigen::Vector2d& offset,
                                                         double stylus_radius,
                                                         const Point2& nominal_center);

}  // namespace pkm::metrology
