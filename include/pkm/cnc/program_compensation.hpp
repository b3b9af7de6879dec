/// @file
/// @brief Pre-distortion of a whole G-code program for a hexapod controller that keeps its
/// nominal kinematics (`pkm gcode compensate`, docs/gcode.md): every motion is interpolated
/// (path_interpolation.hpp, since pre-distortion is nonlinear a straight line is no longer
/// straight), each point goes through compensation::predistortPath (X_cmd =
/// FK_nominal(IK_calibrated(X))), and the program text is rewritten line by line.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "pkm/cnc/interpreter.hpp"
#include "pkm/cnc/path_interpolation.hpp"
#include "pkm/compensation/hybrid_squareness.hpp"
#include "pkm/compensation/predistortion.hpp"
#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::cnc {

/// Settings of compensateProgram.
struct ProgramCompensationOptions {
  InterpolationOptions interpolation;                ///< how motions are cut into G1 segments
  compensation::PredistortionOptions predistortion;  ///< nominal FK settings
  InterpreterOptions interpreter;  ///< how the program is read (tool table for G43 H)
};

/// One compensated point.
struct CompensatedPoint {
  std::size_t line = 0;  ///< source line of the motion
  Axes desired{};        ///< position the program asks for, mm and degrees
  Axes command{};        ///< pre-distorted command written to the output, mm and degrees
};

/// What compensateProgram produced.
struct ProgramCompensation {
  std::string text;                      ///< the compensated program
  std::vector<CompensatedPoint> points;  ///< every commanded point, in order
  std::size_t motion_lines = 0;          ///< source lines whose axis words were replaced
  std::size_t added_lines = 0;           ///< G0/G1 segment and G4 dwell lines inserted after them
  std::size_t offset_lines = 0;          ///< G92 / G10 L20 lines whose axis words were shifted
  double max_correction = 0.0;           ///< largest |command − desired| in XYZ, mm
  /// Executed blocks of a program with O-words, which is flattened first; 0 when it had none.
  std::size_t flattened_blocks = 0;
};

/// Rewrites program `text` (`file` names it in messages). Lines without motion are copied byte
/// for byte. A motion line keeps its N number, comments and other words; its G0/G1/G2/G3 word
/// and axis words (X Y Z A B C, I J K R, and P of an arc) are replaced by `G0` or `G1` and all
/// six pre-distorted axis words, written right after the N number (or at the start). When the
/// motion needs more than one segment, the first is written on the line itself and the others on
/// the following inserted lines `G1 X.. Y.. Z.. A.. B.. C.. (pkm: line L segment k/n)`. The
/// first motion of the program is taken as positioning to its end point (the interpreter's
/// start-up position is not a machine position). A drilling cycle (G73, G81, G82, G83, G85, G89,
/// and a line that repeats one) is expanded: its G word and R, Q, P, L words go too, its first
/// segment is written on the line and the others, each with its own G0 or G1, and the cycle's
/// dwells as `G4 P..` follow as inserted lines; the output has no cycle left, so a G80 stays
/// harmless. The words are in the source line's frame:
/// (machine − offset)/scale with the work, G92 and tool offsets and the unit (G20) in effect,
/// relative to the previous command under G91, machine coordinates under G53 (repeated on the
/// inserted lines). G92 and G10 L20 set an offset from the current position, which on the
/// pre-distorted machine is the last command: their axis words (constants) are shifted by
/// (command − desired)/scale of that point, so that the offset is the source program's. Not
/// supported: G28/G30, G74/G84/G86/G87/G88, G38.x, G33/G76, G93, G4 on a cycle line, and
/// non-constant axis words on a G92/G10 L20 line. A program with O-words (subroutines, loops,
/// conditions) is flattened first (flattenProgram): the output is the flattened program,
/// rewritten, and its "(pkm: line L ...)" comments name lines of the flattened program. Throws
/// pkm::IoError "FILE:LINE: message" (the source line; for a flattened program also the
/// flattened line) for those or when the nominal FK does not converge; pkm::InvalidArgument for
/// bad models.
[[nodiscard]] ProgramCompensation compensateProgram(std::string_view text,
                                                    const std::string& file,
                                                    const kinematics::HexapodModel& nominal,
                                                    const kinematics::HexapodModel& calibrated,
                                                    const ProgramCompensationOptions& options = {});

/// The commands (mm, degrees) for the interpolated points of a program, one per point; may throw
/// pkm::IoError naming a point's line.
using PointMap = std::function<std::vector<Axes>(const std::vector<PathPoint>& points)>;

/// Which of X Y Z A B C a rewritten motion carries.
using AxisMask = std::array<bool, 6>;
/// All six axes.
inline constexpr AxisMask kAllAxes{true, true, true, true, true, true};

/// The rewriting of compensateProgram with any point map: interpolation by `interpolation`, the
/// same subset, line structure and throws. Rewritten motions carry the axis words `axes` names
/// (a machine without a B axis is not sent a B word).
[[nodiscard]] ProgramCompensation rewriteProgram(std::string_view text,
                                                 const std::string& file,
                                                 const PointMap& map,
                                                 const InterpolationOptions& interpolation,
                                                 const AxisMask& axes = kAllAxes,
                                                 const InterpreterOptions& interpreter = {});

/// The hybrid machine's squareness correction of a PKM program (X Y Z = PKM command in its P
/// frame) run with X2 at `x2` (mm): the X2–Y2 part p_c = p + x2·b₁ by G-code, with the base frame
/// (A, b₀) in the controller's kinematic parameters (MXT700S parallelism paper, §3.3); with
/// `base_frame_in_controller` false also p ← A·p + b₀ first (compensation/hybrid_squareness.hpp).
/// A, B, C words are kept. Throws pkm::InvalidArgument for a non-finite x2, and as rewriteProgram.
[[nodiscard]] ProgramCompensation compensateHybridProgram(
    std::string_view text,
    const std::string& file,
    const compensation::HybridSquarenessCompensation& compensation,
    double x2,
    bool base_frame_in_controller,
    const InterpolationOptions& interpolation = {},
    const InterpreterOptions& interpreter = {});

}  // namespace pkm::cnc
