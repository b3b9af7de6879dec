/// @file
/// @brief A Cartesian 3-axis true machine with the 21 ISO 230-1 geometric errors: 18 component
/// errors (six per axis, as tables over the axis position) and three squareness errors, composed
/// as homogeneous transforms (docs/conventions.md, "Cartesian virtual machine"). Used for the
/// diagonal methods of Hwang et al. ("Analysis of multi-axis volumetric errors").
#pragma once

#include <array>
#include <optional>
#include <string>

#include "pkm/geometry/error_table.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/simulation/environment.hpp"
#include "pkm/simulation/random.hpp"
#include "pkm/simulation/virtual_machine.hpp"

namespace pkm::simulation {

/// The three squareness errors of a Cartesian machine, radians, in the project convention: the
/// included angle between the positive directions of the two axes minus 90°, positive when larger.
/// X is the reference direction, Y lies in the xy plane of the work frame.
struct CartesianSquareness {
  double xy = 0.0;  ///< ∠(+X, +Y) − 90°; ISO 230-1 EC0Y = +xy
  double xz = 0.0;  ///< ∠(+X, +Z) − 90°; ISO 230-1 EB0Z = −xz
  double yz = 0.0;  ///< ∠(+Y, +Z) − 90°; ISO 230-1 EA0Z = +yz
};

/// The 21 geometric errors. axes[0..2] are X, Y, Z; an absent table is zero. Each table has six
/// columns in ErrorMotion order, the error motion of the axis's moving frame in its own axes:
/// for X, [EXX, EYX, EZX, EAX, EBX, ECX] (mm and rad) as functions of the commanded x.
struct CartesianErrors {
  std::array<std::optional<geometry::ErrorTable1d>, 3> axes;  ///< X, Y, Z component errors
  CartesianSquareness squareness;                             ///< EC0Y, EB0Z, EA0Z
  /// Throws pkm::InvalidArgument when a table does not have six columns or a squareness is not
  /// finite.
  void validate() const;
};

/// The nominal layout of a Cartesian machine.
struct CartesianLayout {
  /// The axis stacking, from the work (bed) to the tool: a permutation of "XYZ". "XYZ" means X
  /// moves on the bed, Y is carried by X, Z by Y and the tool by Z. All three axes move the tool;
  /// the work is fixed to the bed.
  std::string order = "XYZ";
  /// The tool point in the frame of the last axis of `order` at command (0, 0, 0) relative to that
  /// frame's origin, mm. The rotations of every axis act on it (Abbe offsets of the tool).
  Eigen::Vector3d tool_offset = Eigen::Vector3d::Zero();
  /// Throws pkm::InvalidArgument unless `order` is a permutation of "XYZ" and the offset finite.
  void validate() const;
};

/// How the axes follow their commands (direction-dependent reversal and positioning scatter, the
/// effects ISO 230-2 §2.12-2.14 reports as reversal value B and repeatability R).
struct CartesianActuation {
  /// Per axis (X, Y, Z) lost motion, mm, ≥ 0: an axis that last moved in + stops b/2 short of its
  /// command, one that last moved in − stops b/2 above it, so ISO 230-2's reversal value at every
  /// target is B_i = x̄_i↑ − x̄_i↓ = −b. After reset() an axis counts as having moved in +.
  Eigen::Vector3d backlash = Eigen::Vector3d::Zero();
  /// Per axis standard deviation of the position reached by a move, mm (ISO 230-2's s_i↑, s_i↓).
  /// Drawn once per move of an axis whose command changes; an axis that does not move stays put.
  Eigen::Vector3d repeatability_sigma = Eigen::Vector3d::Zero();
  /// Throws pkm::InvalidArgument for a negative or non-finite value.
  void validate() const;
};

/// A Cartesian 3-axis virtual machine. Command (x, y, z), mm. Axis k moves its frame by
/// Trans(q_k·d_k)·E_k(q_k) relative to its carrier, where d_k is the actual direction of motion
/// (d_X = x̂; d_Y = Rz(xy)·ŷ = (−sin xy, cos xy, 0); d_Z the unit vector on the +z side with
/// d_Z·d_X = −sin xz and d_Z·d_Y = −sin yz, to first order (−xz, −yz, 1); in the carrier's axes)
/// and E_k the error motion of the axis's table at the commanded q_k:
///   work_T_tool = Π over `order` [Trans(q_k·d_k)·E_k(q_k)] · Trans(tool_offset).
/// Without component errors the frames stay parallel to the work frame and the three squareness
/// errors are exact, alone or together; with component errors the angles between the lines of
/// motion hold to first order. With a CartesianActuation, q_k in the translation is the position
/// the axis actually reaches: q_k − (b_k/2)·(approach direction) + its repeatability draw; the
/// error tables are still evaluated at the commanded q_k.
class CartesianMachine final : public VirtualMachine {
 public:
  /// Throws pkm::InvalidArgument when layout.validate(), errors.validate() or
  /// actuation.validate() fails.
  CartesianMachine(CartesianLayout layout,
                   CartesianErrors errors,
                   CartesianActuation actuation = {});
  [[nodiscard]] std::vector<std::string> axisNames() const override;
  /// Trans((x, y, z) + tool_offset).
  [[nodiscard]] geometry::RigidTransform nominalPose(const Eigen::VectorXd& command) const override;
  /// The composition in the class comment. Throws pkm::InvalidArgument for a bad command or when a
  /// table with the `kThrow` policy does not cover it.
  geometry::RigidTransform moveTo(const Eigen::VectorXd& command) override;
  /// The layout.
  [[nodiscard]] const CartesianLayout& layout() const { return layout_; }
  /// The injected errors (the truth).
  [[nodiscard]] const CartesianErrors& errors() const { return errors_; }
  /// The actuation (the truth).
  [[nodiscard]] const CartesianActuation& actuation() const { return actuation_; }
  /// Forgets the approach directions and seeds the repeatability noise.
  void reset(std::uint64_t noise_seed) override;
  /// The actual unit direction of motion of axis k (0 = X) in its carrier's axes (class comment).
  /// Precondition: |xy| < 90° and the three angles describe a real direction (|xy|, |xz|, |yz|
  /// small); throws pkm::InvalidArgument for k outside 0..2.
  [[nodiscard]] Eigen::Vector3d axisDirection(int k) const;
  /// Gravity sag of the axes X, Y, Z (environment.hpp AxisSag, compliance.hpp): after the
  /// composition above, for each axis k in `order` whose sag is not kNone, the tool pose becomes
  /// sagCarryingTool(pose, axisDeflection(sag_k, q_k), sense_k·ê_k, pivot_k) with ê_k the axis's
  /// nominal unit direction and pivot_k the nominal position of its carriage (the commands of the
  /// axes up to and including k in `order`, work frame). All kNone (the default) switches it off.
  /// Throws pkm::InvalidArgument for an invalid sag.
  void setSag(const std::array<AxisSag, 3>& sag);
  /// The sag in effect.
  [[nodiscard]] const std::array<AxisSag, 3>& sag() const { return sag_; }

 private:
  CartesianLayout layout_;
  CartesianErrors errors_;
  CartesianActuation actuation_;
  RandomStream rng_{0};
  Eigen::Vector3d last_ = Eigen::Vector3d::Zero();    // last command
  Eigen::Vector3d offset_ = Eigen::Vector3d::Zero();  // actual − commanded axis position
  Eigen::Vector3i approach_ = Eigen::Vector3i::Ones();
  bool moved_ = false;
  std::array<AxisSag, 3> sag_{};
};

}  // namespace pkm::simulation
