/// @file
/// @brief Dependent rotational motion (DRM) of an Exechon: the uncontrolled rotation of the tool
/// about its own axis that the 5-axis mechanism makes as the tool moves with a fixed direction
/// (Lee, Lee, Yang, "Accuracy Improvement of On-Machine Measurement for the Parallel Kinematic
/// Machine Considering Constraint Motion", JKSPE 36(5):463-469, 2019, sec. 2.3, eqs. 6, 7 and 10).
///
/// Definition used here. H is a frame that keeps the reference tool orientation (world_R_H =
/// world_R_tool at the reference pose). With M = H_R_tool = world_R_toolᵀ_ref · world_R_tool, φ_DRM
/// is the twist of M about the tool axis z (swing-twist decomposition, M = swing · Rz(φ)):
///   φ_DRM = atan2(M(1,0) − M(0,1), M(0,0) + M(1,1)),
/// which equals φ when the tool direction is the reference one (M = Rz(φ)). It is the rotation of
/// the tool frame relative to H, positive about the tool direction. The paper writes the inverse,
/// ^A R_H = Rz(−φ) (eq. 6), and its eq. (7) atan2(a11, a21) as printed would not vanish at the
/// reference; φ_DRM here is 0 at the reference pose by construction.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "pkm/kinematics/exechon_data.hpp"
#include "pkm/kinematics/exechon_model.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"

namespace pkm::kinematics {

/// φ_DRM (rad, in (−pi, pi]) of the tool frame `world_R_tool` relative to the reference tool frame
/// (see the file comment). Undefined (returns 0) only when the tool direction is reversed.
[[nodiscard]] double dependentRotation(const Eigen::Matrix3d& world_R_tool,
                                       const Eigen::Matrix3d& world_R_tool_reference);

/// φ_DRM at tool pose `pose` relative to `reference`: tool IK at the reference (model branch, wrist
/// nearest home), then at `pose` by continuity from the reference configuration. On success *phi
/// holds φ_DRM (rad) and data the solution at `pose`. Returns the first failing IK status
/// otherwise.
ExechonIkStatus dependentRotation(const ExechonModel& model,
                                  ExechonData& data,
                                  const ExechonToolPose& pose,
                                  const ExechonToolPose& reference,
                                  double* phi);

/// A circle of tool points with a constant tool direction (a circular test on a ring gauge, seed
/// paper sec. 4). Points p(θ) = centre + radius·(cos θ·x̂ + sin θ·ŷ), θ right-handed about the
/// direction, with x̂ the world x axis projected onto the circle's plane (the world y axis when x is
/// within 25° of the direction) and ŷ = direction × x̂.
struct DrmCircleOptions {
  Eigen::Vector3d centre =
      Eigen::Vector3d::Zero();  ///< world, model length unit; the DRM reference
  Eigen::Vector3d direction =
      -Eigen::Vector3d::UnitZ();  ///< tool direction = plane normal (normalised)
  double radius = 0.0;            ///< model length unit, > 0
  /// Requested angle step (rad). The circle [0, 2·pi] is split into N = ceil(2·pi/step) equal steps
  /// (N >= 5).
  double step = 0.0174532925199432958;  // 1°

  /// True when every field is usable; otherwise false with the reason in *why (if given).
  [[nodiscard]] bool isValid(std::string* why = nullptr) const;
};

/// The sampled DRM along a circle and its 5th-order polynomial model (seed paper eq. 10).
struct DrmCircleResult {
  ExechonIkStatus status =
      ExechonIkStatus::kOk;   ///< the first failing IK status (then the table stops)
  int failed_index = -1;      ///< the point that failed (-1: the centre or none)
  std::vector<double> theta;  ///< rad, 0 .. 2·pi
  std::vector<double> phi;  ///< φ_DRM relative to the tool at the centre, rad, unwrapped along θ
  /// c0..c5 of φ(θ) ≈ Σ c_n·θⁿ (θ in rad), least squares (eq. 10).
  std::array<double, 6> coefficients{};
  double max_fit_deviation =
      0.0;                   ///< max |φ − fit| over the samples, rad (the paper reports < 0.1°)
  double max_abs_phi = 0.0;  ///< max |φ| over the samples, rad
  [[nodiscard]] bool ok() const { return status == ExechonIkStatus::kOk; }
};

/// Samples φ_DRM around the circle: tool IK at the centre (the reference; model branch, wrist
/// nearest home), then at each point by continuity from the previous one, then fits eq. (10).
/// Limits are not checked. Throws pkm::InvalidArgument if `options` is invalid.
[[nodiscard]] DrmCircleResult sampleDrmCircle(const ExechonModel& model,
                                              ExechonData& data,
                                              const DrmCircleOptions& options);

/// Least-squares coefficients c0..c5 of φ(θ) ≈ Σ c_n·θⁿ. Throws pkm::InvalidArgument unless the two
/// vectors have the same size >= 6 and are finite.
[[nodiscard]] std::array<double, 6> fitDrmPolynomial(const std::vector<double>& theta,
                                                     const std::vector<double>& phi);

/// Σ c_n·θⁿ (Horner).
[[nodiscard]] double evaluateDrmPolynomial(const std::array<double, 6>& coefficients, double theta);

}  // namespace pkm::kinematics
