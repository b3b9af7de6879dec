/// @file
/// @brief Joint-space conversion of interpolated G-code points for a hexapod: machine
/// coordinates X Y Z A B C = TCP pose of the platform in the work frame (project pose
/// convention, R = Rz(C)·Ry(B)·Rx(A); degrees in G-code, radians inside), strut readings by the
/// closed-form inverse kinematics (kinematics/hexapod_ik.hpp), and the joint CSV of `pkm gcode
/// run`.
#pragma once

#include <string>
#include <vector>

#include "pkm/cnc/path_interpolation.hpp"
#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::cnc {

/// The pose of machine position `pos` (mm, degrees) in a model whose length unit is `unit`:
/// position divided by millimetresPer(unit), angles converted to radians.
[[nodiscard]] kinematics::PoseRpy poseFromAxes(const Axes& pos, LengthUnit unit);

/// Interpolation settings for joint-space output with chordal tolerance `tolerance` (mm): arcs by
/// the sagitta rule, and a maximum step so that a controller interpolating linearly in joint
/// space between samples stays near the Cartesian path. A strut reading q(s) = |x(s) − b| along
/// a straight TCP line has |q''| <= 1/L (L the joint distance), so linear interpolation between
/// samples h apart deviates from it by at most h²/(8·L) (chord error of a curve of curvature
/// 1/L); max_step = sqrt(8·tol·L_min)/2 (L_min the shortest joint distance the strokes allow,
/// factor 1/2 for the Jacobian's amplification, checked against FK of a dense reference in
/// joint_path_test). A/B/C: a platform joint r from the TCP moves on a circle, chord error
/// r·(1 − cos(Δθ/2)) <= tol/4 gives max_angle_step = 2·acos(1 − tol/(4·r_max)). Throws
/// pkm::InvalidArgument when tolerance is not > 0.
[[nodiscard]] InterpolationOptions jointSpaceInterpolation(const kinematics::HexapodModel& model,
                                                           double tolerance);

/// Converts machine positions to strut readings with one model and one workspace (not
/// thread-safe: one converter per thread).
class HexapodJointConverter {
 public:
  /// Keeps a reference to `model` (which must outlive the converter); throws
  /// pkm::InvalidArgument when the model fails validate().
  explicit HexapodJointConverter(const kinematics::HexapodModel& model);

  /// Strut readings (model length unit) at `pos` (mm, degrees); leaves the workspace at that
  /// pose (data()). Readings outside the stroke are returned as they are (checks report them).
  const kinematics::StrutVector& solve(const Axes& pos);

  /// Converts every point; q[i] are the readings of points[i].
  void solveAll(const std::vector<PathPoint>& points, std::vector<kinematics::StrutVector>& q);

  [[nodiscard]] const kinematics::HexapodModel& model() const { return *model_; }
  [[nodiscard]] kinematics::HexapodData& data() { return data_; }

 private:
  const kinematics::HexapodModel* model_;
  kinematics::HexapodData data_;
};

/// Header of the joint CSV: `line,t,x,y,z,a,b,c,q0,q1,q2,q3,q4,q5`.
inline constexpr const char* kJointCsvHeader = "line,t,x,y,z,a,b,c,q0,q1,q2,q3,q4,q5";

/// Appends one joint CSV row with its newline: source line, time t (s), the position (mm,
/// degrees) and the six readings (model length unit), numbers in shortest round-trip form.
void appendJointCsv(std::string& out,
                    const PathPoint& point,
                    double t,
                    const kinematics::StrutVector& q);

}  // namespace pkm::cnc
