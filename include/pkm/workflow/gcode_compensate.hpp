/// @file
/// @brief `pkm gcode compensate` as a workflow (docs/gcode.md "gcode compensate"): a program
/// pre-distorted for a controller that keeps the nominal kinematics of a calibrated hexapod or
/// Exechon (X_cmd = FK_nominal(IK_calibrated(X)), docs/compensation.md), or the hybrid machine's
/// X2–Y2 squareness corrected in a PKM program from a campaign's pkm-base-frame.txt (MXT700S
/// parallelism paper).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "pkm/cnc/program_compensation.hpp"
#include "pkm/io/exechon_machine.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/workflow/gcode_interpreter.hpp"

namespace pkm::workflow {

/// A `gcode compensate` request: either `machine` or `hybrid_frame` with `x2`.
struct GcodeCompensateRequest {
  io::NamedText program;  ///< the program; its name prefixes every message (NAME:LINE: ...)
  /// The calibrated machine: the output of `pkm calibrate hexapod|exechon --out` (a file or a
  /// built-in name).
  std::string machine;
  /// A calibrated machine a front end has already loaded (e.g. a Python calibration's
  /// result.machine), used instead of `machine`; at most one of `machine`, `hexapod` and
  /// `exechon` is set.
  std::shared_ptr<const io::HexapodMachine> hexapod;
  std::shared_ptr<const io::ExechonMachine> exechon;
  /// The controller's nominal machine ("" : the built-in machine the calibrated machine's name
  /// refers to, its name without "-calibrated").
  std::string nominal;
  /// Hexapod: the LinuxCNC INI the program runs under ("" : the one a `.hal` nominal machine
  /// finds beside it, if any). Its RS274NGC_STARTUP_CODE runs before the program (so a G20 there
  /// makes the program's numbers inches), and its [TRAJ] LINEAR_UNITS must be the machine's.
  std::string ini;
  /// Chordal tolerance of the interpolation in the machine's length unit (> 0; hybrid: mm);
  /// default 0.01 mm.
  std::optional<double> tolerance;
  /// The most interpolated points the program may need (> 0; cnc::InterpolationOptions).
  std::size_t max_points = cnc::kDefaultMaxPathPoints;
  std::string out;     ///< the file to write ("" : none, the caller shows the text)
  bool force = false;  ///< replace an existing `out`
  std::string
      hybrid_frame;  ///< hybrid machine: pkm-base-frame.txt of a campaign (docs/campaign.md)
  std::optional<double> x2;  ///< hybrid machine: the X2 position the program runs at, mm
  /// Hybrid machine: also apply the base frame's rotation and offset in the program.
  bool frame_not_in_controller = false;
  /// Exechon: what A/C mean, "vector" (default) or "axes", as in `gcode run`.
  std::optional<std::string> orientation;
  GcodeInterpreterSettings interpreter;  ///< the tool table (G43 H)
  /// The calibrated machine's name in messages: `machine`, or the loaded machine's model name.
  [[nodiscard]] std::string machineName() const;
  /// Whether the calibrated machine is an Exechon (`exechon` set, or `machine` names one).
  [[nodiscard]] bool onExechon() const;
  /// Throws pkm::InvalidArgument for a tolerance that is not > 0, neither or both of a machine
  /// (`machine`, `hexapod` or `exechon`, at most one) and `hybrid_frame`, a hybrid frame without
  /// `x2`, an orientation for a hexapod or an INI for an Exechon or hybrid machine; pkm::IoError
  /// "OUT exists; pass --force to overwrite it" when `out` exists and `force` is not set.
  void validate() const;
};

/// A compensated program.
struct GcodeCompensateResult {
  cnc::ProgramCompensation compensation;  ///< the text, the line counts, the largest correction
  /// One line saying what was compensated, the line counts and the largest correction, no
  /// newline.
  std::string note;
};

/// Reads the machines (or the base frame), compensates the program and, when `out` is set,
/// writes it through io::AtomicFile. Throws pkm::IoError for unreadable machine or frame files
/// (FILE:LINE) and programs the compensation rejects (NAME:LINE: message), pkm::InvalidArgument
/// for a nominal machine that cannot be told or does not match, an INI whose LINEAR_UNITS differ
/// from the machine's, and as validate().
[[nodiscard]] GcodeCompensateResult compensateGcode(const GcodeCompensateRequest& request);

}  // namespace pkm::workflow
