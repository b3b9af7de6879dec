/// @file
/// @brief A hexapod true machine: the nominal model the controller believes in, plus injected
/// assembly errors (joint positions, strut length offsets) and actuator effects (encoder
/// resolution, per-strut backlash, repeatability), as Lee et al. ("Development of a Parallel-Typed
/// CNC Machine") describe them.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_model.hpp"
#include "pkm/simulation/environment.hpp"
#include "pkm/simulation/random.hpp"
#include "pkm/simulation/unmodelled_geometry.hpp"
#include "pkm/simulation/virtual_machine.hpp"

namespace pkm::simulation {

/// Assembly errors: the true geometry minus the nominal one, model length unit (mm).
struct HexapodAssemblyErrors {
  /// Per strut: true − nominal base joint centre, world frame.
  std::array<Eigen::Vector3d, kinematics::kStruts> base_joint;
  /// Per strut: true − nominal platform joint centre, platform frame.
  std::array<Eigen::Vector3d, kinematics::kStruts> platform_joint;
  /// Per strut: true − nominal length offset (reading + offset = joint distance).
  kinematics::StrutVector length_offset = kinematics::StrutVector::Zero();
  /// No errors.
  HexapodAssemblyErrors() {
    base_joint.fill(Eigen::Vector3d::Zero());
    platform_joint.fill(Eigen::Vector3d::Zero());
  }
  /// The true model: `nominal` with these errors added.
  [[nodiscard]] kinematics::HexapodModel apply(const kinematics::HexapodModel& nominal) const;
};

/// How the struts follow their commands.
struct StrutActuation {
  /// Encoder resolution, mm: a commanded reading is positioned to the nearest count (0: exact).
  double encoder_resolution = 0.0;
  /// Per-strut backlash (lost motion), mm, ≥ 0: a strut that last moved in +reading stops b/2
  /// short of its command, one that last moved in − b/2 beyond it (Lee et al., "Development of a
  /// Parallel-Typed CNC Machine", Fig. 6 hysteresis). After reset() a strut counts as having moved
  /// in +.
  kinematics::StrutVector backlash = kinematics::StrutVector::Zero();
  /// Standard deviation of a strut's positioning per move, mm (Lee et al., "Development of a
  /// Parallel-Typed CNC Machine": about 2 µm overall).
  double repeatability_sigma = 0.0;
  /// Throws pkm::InvalidArgument for a negative or non-finite value.
  void validate() const;
};

/// A hexapod virtual machine. Command (x, y, z, a, b, c): the TCP pose the controller is asked
/// for, mm and radians (R = Rz(c)·Ry(b)·Rx(a), docs/conventions.md "Pose"). The controller turns
/// it into strut readings with the nominal model (inverseKinematics); the struts reach them
/// through StrutActuation; the platform then sits where the true model's forward kinematics puts
/// it (seeded with the previous actual pose, or the command for the first move after reset). Poses
/// are world_T_tool with the world (base) frame as the work frame. With unmodelled geometry
/// (setUnmodelledGeometry) each strut travels its reading plus its screw's lead error, and the
/// struts' lines pass through the U-joints' shifted points (UJointOffset): the platform sits where
/// those joint distances close the loops.
class HexapodVirtualMachine final : public VirtualMachine {
 public:
  /// Throws pkm::InvalidArgument when either model does not validate, the unit is not mm, or
  /// the actuation is invalid.
  HexapodVirtualMachine(kinematics::HexapodModel nominal,
                        const HexapodAssemblyErrors& errors,
                        StrutActuation actuation = {});
  /// {"x", "y", "z", "a", "b", "c"} (angles in radians here; degrees only at file boundaries).
  [[nodiscard]] std::vector<std::string> axisNames() const override;
  /// a, b, c.
  [[nodiscard]] std::vector<bool> angularAxes() const override {
    return {false, false, false, true, true, true};
  }
  /// The actuation (the truth).
  [[nodiscard]] const StrutActuation& actuation() const { return actuation_; }
  /// The commanded pose.
  [[nodiscard]] geometry::RigidTransform nominalPose(const Eigen::VectorXd& command) const override;
  /// Commands the struts and returns the true pose. Throws pkm::InvalidArgument when the true
  /// machine's forward kinematics does not converge (the command is far outside the workspace).
  geometry::RigidTransform moveTo(const Eigen::VectorXd& command) override;
  /// Forgets the approach directions and seeds the repeatability noise.
  void reset(std::uint64_t noise_seed) override;
  /// The strut readings commanded by the last moveTo (nominal IK, quantised), mm.
  [[nodiscard]] const kinematics::StrutVector& commandedReadings() const { return commanded_; }
  /// The nominal model (commands are poses of this machine).
  [[nodiscard]] const kinematics::HexapodModel& nominal() const { return nominal_; }
  /// The model the controller's inverse kinematics uses (the nominal model until
  /// setControllerModel).
  [[nodiscard]] const kinematics::HexapodModel& controller() const { return controller_; }
  /// Compensation by calibrated kinematics: the controller turns commands into strut readings with
  /// `model` (e.g. a calibrated model loaded into LinuxCNC's genhexkins). Equivalent to sending
  /// pre-distorted commands FK_nominal(IK_model(X)) to a nominal controller. Throws
  /// pkm::InvalidArgument when `model` does not validate or its unit is not mm.
  void setControllerModel(kinematics::HexapodModel model);
  /// The true model (the truth).
  [[nodiscard]] const kinematics::HexapodModel& truth() const { return true_; }
  /// Thermal growth of the struts (environment.hpp): every strut's joint distance (reading +
  /// length offset) is (1 + `relative`) times what the actuation gives, e.g. α·ΔT = 11.5e-6 ×
  /// 2 K. 0 (the default) leaves the struts as they are. Throws pkm::InvalidArgument unless finite
  /// and > −1.
  void setStrutGrowth(double relative);
  /// The current relative strut growth.
  [[nodiscard]] double strutGrowth() const { return growth_; }
  /// Gravity compliance and joint clearance (environment.hpp, compliance.hpp): at every move the
  /// struts' axial forces C under the platform's and struts' weight at the commanded pose
  /// (hexapodStrutLoads with the controller's model and IK) change each strut's joint distance by
  /// legDeflection (−C/k, and the joint clearance taken up in the force's direction), and the true
  /// model's FK places the platform there. std::nullopt (the default) switches it off. Throws
  /// pkm::InvalidArgument for an invalid compliance.
  void setCompliance(std::optional<HexapodCompliance> compliance);
  /// The compliance in effect.
  [[nodiscard]] const std::optional<HexapodCompliance>& compliance() const { return compliance_; }
  /// The strut forces of the last move, N, compression positive (zero without compliance).
  [[nodiscard]] const kinematics::StrutVector& strutLoads() const { return loads_; }
  /// The geometry beyond the model (unmodelled_geometry.hpp; the truth): strut i's joint distance
  /// is r + e_i(r) + length offset for the actuated reading r (before thermal growth), between the
  /// joint centres shifted by base_joint[i].shift(u) (world) and platform_joint[i].shift(Rᵀu)
  /// (platform frame), u the strut's unit vector from base to platform and R the platform's
  /// rotation. A zero geometry (the default) leaves the machine as it was. Throws
  /// pkm::InvalidArgument when `geometry` does not validate.
  void setUnmodelledGeometry(const HexapodUnmodelledGeometry& geometry);
  /// The current unmodelled geometry.
  [[nodiscard]] const HexapodUnmodelledGeometry& unmodelledGeometry() const { return geometry_; }

 private:
  kinematics::HexapodModel nominal_;
  kinematics::HexapodModel true_;
  kinematics::HexapodModel controller_;
  StrutActuation actuation_;
  kinematics::HexapodData controller_data_;
  kinematics::HexapodData true_data_;
  RandomStream rng_{0};
  kinematics::StrutVector commanded_ = kinematics::StrutVector::Zero();
  kinematics::StrutVector last_ = kinematics::StrutVector::Zero();
  std::array<int, kinematics::kStruts> approach_{};
  bool moved_ = false;
  kinematics::PoseRpy last_pose_;
  double growth_ = 0.0;
  std::optional<HexapodCompliance> compliance_;
  kinematics::StrutVector loads_ = kinematics::StrutVector::Zero();
  std::array<int, kinematics::kStruts> load_side_{};  // side the joint clearance is taken up on
  HexapodUnmodelledGeometry geometry_;
  kinematics::HexapodModel shifted_;  ///< true_ with the U-joint shifts of the last pose
  /// The true FK of `actual` with the U-joint shifts, by fixed-point iteration on the shifts.
  kinematics::FkSummary trueForward(const kinematics::StrutVector& actual,
                                    const kinematics::PoseRpy& seed);
};

}  // namespace pkm::simulation
