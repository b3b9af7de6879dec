/// @file
/// @brief G-code pre-distortion for an Exechon whose controller keeps the nominal kinematics:
/// every interpolated point X becomes X_cmd = FK_nominal(IK_calibrated(X)), so that the nominal
/// controller commands the leg and wrist readings the real (calibrated) machine needs. Same
/// rewriting rules as program_compensation.hpp.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <string_view>

#include "pkm/cnc/exechon_path.hpp"
#include "pkm/cnc/program_compensation.hpp"
#include "pkm/kinematics/exechon_model.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"

namespace pkm::cnc {

/// A and C (degrees) of the virtual C/A head that point the tool along `direction` (world
/// frame, non-zero): the inverse of toolDirectionFromAngles. Of the two solutions (A, C) and
/// (−A, C + 180°), each shifted by multiples of 360°, returns the one nearest (a_near, c_near)
/// (|ΔA| + |ΔC|); for a vertical tool (A = 0 or 180°) C is undefined and c_near is kept.
/// Throws pkm::InvalidArgument for a zero or non-finite direction.
[[nodiscard]] std::array<double, 2> toolAnglesFromDirection(const Eigen::Vector3d& direction,
                                                            double a_near,
                                                            double c_near);

/// Options of compensateExechonProgram.
struct ExechonProgramCompensationOptions {
  ExechonOrientation orientation = ExechonOrientation::kToolVector;  ///< what A/C mean
  InterpolationOptions interpolation;  ///< e.g. exechonInterpolation(calibrated, tolerance)
  kinematics::FkOptions fk;            ///< the nominal tool FK's settings
  InterpreterOptions interpreter;      ///< how the program is read (tool table for G43 H)
};

/// Pre-distorts an Exechon program. X Y Z are the tool point in the machine's world frame, A/C
/// as `options.orientation` says (gcode run's conventions; B must be 0). Each point is solved on
/// `calibrated` by continuity (ExechonJointConverter), then the nominal tool FK of those readings
/// (seeded by the previous point) gives the command: X Y Z its tool point; A, C its tool
/// direction (kToolVector, nearest the desired A, C) or the wrist readings (kWristAxes). Lines as
/// rewriteProgram, with X Y Z A C words (no B). Throws pkm::IoError "FILE:LINE: message" where the
/// calibrated machine cannot reach a point, B is programmed, or the nominal FK fails;
/// pkm::InvalidArgument for invalid models or models in different length units.
[[nodiscard]] ProgramCompensation compensateExechonProgram(
    std::string_view text,
    const std::string& file,
    const kinematics::ExechonModel& nominal,
    const kinematics::ExechonModel& calibrated,
    const ExechonProgramCompensationOptions& options);

}  // namespace pkm::cnc
