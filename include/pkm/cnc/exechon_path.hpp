/// @file
/// @brief Joint-space conversion of interpolated G-code points for an Exechon tripod with its C/A
/// wrist (`pkm gcode run` on an Exechon machine; docs/gcode.md "Exechon machines"). X Y Z are the
/// tool point in the machine's world frame (mm); A and C are read in one of two ways:
/// - kToolVector: A and C (degrees) give the tool vector of a virtual C/A head in the world frame,
///   k = Rz(C)·Rx(A)·ẑ (from the tool point towards the spindle, the CAM convention; A = C = 0 is
///   a vertical tool), and the wrist readings follow from the tool IK by continuity;
/// - kWristAxes: A and C are the wrist axes' readings themselves (degrees, as a LinuxCNC TCP
///   kinematics reads rotary words), and the tripod parameters e solve S(e) + L·R(e)·u = tool
///   point, u the tool direction the readings give in the platform frame
///   (kinematics::toolPointInverseKinematics, started from the extrapolation of the last three
///   solutions).
/// B must be 0 (an Exechon has no B axis). Each point is solved by continuity from the previous
/// one (tripod branch and wrist branch nearest), starting from the machine's home.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "pkm/cnc/path_interpolation.hpp"
#include "pkm/kinematics/exechon_data.hpp"
#include "pkm/kinematics/exechon_ik.hpp"
#include "pkm/kinematics/exechon_model.hpp"
#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::cnc {

/// How the A and C words of a program orient the tool (see the file comment).
enum class ExechonOrientation { kToolVector, kWristAxes };

/// "vector", "axes".
[[nodiscard]] std::string_view toString(ExechonOrientation o);

/// Parses "vector" or "axes". Throws pkm::InvalidArgument otherwise.
[[nodiscard]] ExechonOrientation parseExechonOrientation(std::string_view text);

/// The world tool direction (from spindle to tool point, unit) of the virtual head at A, C
/// (degrees): −Rz(C)·Rx(A)·ẑ = (−sin C·sin A, cos C·sin A, −cos A).
[[nodiscard]] Eigen::Vector3d toolDirectionFromAngles(double a_deg, double c_deg);

/// Interpolation settings for an Exechon with chordal tolerance `tolerance` (mm), by the rules of
/// jointSpaceInterpolation (joint_path.hpp): max_step = sqrt(8·tol·L_min)/2 with L_min the
/// shortest leg length the strokes allow; max_angle_step = 2·acos(1 − tol/(4·r)) with r the tool
/// length plus the farthest platform joint from S (a joint swings on that radius when the tool
/// turns about its point). Throws pkm::InvalidArgument when tolerance is not > 0.
[[nodiscard]] InterpolationOptions exechonInterpolation(const kinematics::ExechonModel& model,
                                                        double tolerance);

/// One converted point.
struct ExechonPathSample {
  kinematics::ExechonIkStatus status = kinematics::ExechonIkStatus::kOk;  ///< of this point
  kinematics::ExechonConfiguration config;  ///< (alpha, beta, h), wrist C, A (rad); when ok
  Eigen::Vector3d readings = Eigen::Vector3d::Zero();   ///< legs A, B, C, model length unit
  Eigen::Vector3d direction = Eigen::Vector3d::Zero();  ///< tool direction, world frame
  double drm = 0.0;  ///< φ_DRM of the tool frame relative to the first point's, rad
  /// Joint vector for rates and cycle time: legs A, B, C (length unit), wrist C, A (degrees), 0.
  /// For a failed point, the last good point's (the rates then see no motion there).
  kinematics::StrutVector joints = kinematics::StrutVector::Zero();
  [[nodiscard]] bool ok() const { return status == kinematics::ExechonIkStatus::kOk; }
};

/// Converts machine positions to Exechon joints by continuity (not thread-safe).
class ExechonJointConverter {
 public:
  /// Keeps a reference to `model` (which must outlive the converter). Throws
  /// pkm::InvalidArgument when the model fails validate().
  ExechonJointConverter(const kinematics::ExechonModel& model, ExechonOrientation orientation);

  /// Solves `pos` (mm, degrees) by continuity from the last successful point (the home
  /// configuration at first). A failure leaves the previous solution in place. A non-zero B is
  /// kInvalidInput (the caller reports the line). kWristAxes: the status of
  /// kinematics::toolPointInverseKinematics (kSingular when Newton's method fails).
  ExechonPathSample solve(const Axes& pos);

  /// Converts every point.
  void solveAll(const std::vector<PathPoint>& points, std::vector<ExechonPathSample>& out);

  [[nodiscard]] kinematics::ExechonData& data() { return data_; }

 private:
  kinematics::ExechonIkStatus solveVector(const Eigen::Vector3d& p, const Eigen::Vector3d& u);
  kinematics::ExechonIkStatus solveAxes(const Eigen::Vector3d& p, double c, double a);
  const kinematics::ExechonModel* model_;
  ExechonOrientation orientation_;
  kinematics::ExechonData data_;
  kinematics::ExechonConfiguration previous_;
  kinematics::StrutVector last_joints_ = kinematics::StrutVector::Zero();
  bool have_reference_ = false;
  /// kWristAxes: e of the two solutions before previous_ (newest first) and how many consecutive
  /// solved points previous_ ends (0 for the home, at most 3): Newton's start is their
  /// extrapolation.
  std::array<Eigen::Vector3d, 2> older_e_{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  int solved_in_row_ = 0;
  Eigen::Matrix3d reference_R_ = Eigen::Matrix3d::Identity();
};

/// Header of the Exechon joint CSV.
inline constexpr const char* kExechonJointCsvHeader =
    "line,t,x,y,z,a,b,c,q1,q2,q3,wrist_c,wrist_a,ux,uy,uz,drm";

/// Appends one Exechon joint CSV row with its newline: line, t (s), position (mm, degrees), leg
/// readings (model length unit), wrist C and A (degrees), the world tool direction and φ_DRM
/// (degrees); the joint fields are empty for a point that could not be solved.
void appendExechonJointCsv(std::string& out,
                           const PathPoint& point,
                           double t,
                           const ExechonPathSample& sample);

}  // namespace pkm::cnc
