/// @file
/// @brief LinuxCNC genhexkins interop: read a `kinematics.hal` (+ its INI) into a HexapodMachine
/// and write the `setp` block back (docs/machine-format.md, "LinuxCNC").
#pragma once

#include <array>
#include <optional>
#include <string>

#include "pkm/io/hexapod_machine.hpp"
#include "pkm/io/named_text.hpp"

namespace pkm::io {

/// How to find the INI file that goes with a HAL file.
struct HalReadOptions {
  /// INI to read ([TRAJ] HOME, LINEAR_UNITS; [JOINT_n] MIN_LIMIT/MAX_LIMIT as strut stroke,
  /// MAX_VELOCITY/MAX_ACCELERATION as joint_rates, the smallest of the joints).
  std::optional<std::string> ini_path;
  /// Without ini_path: use the one *.ini file in the HAL file's folder whose [HAL] HALFILE lines
  /// name the HAL file (a notice says which). Without any INI: units mm, home 0 0 0 0 0 0 (with a
  /// notice).
  bool discover_ini = true;
};

/// Reads `setp genhexkins.base.N.x|y|z`, `platform.N.x|y|z`, `spindle-offset`, `tool-offset`,
/// `convergence-criterion`, `limit-iterations`, and the comment lines `# pkm: home = x y z a b c`
/// and
/// `# pkm: units = mm|inch` that writeLinuxcncSetp emits (an INI overrides them). Other lines
/// become notices; `screw-lead` != 0 is an error (the screw-twist correction is not modelled). All
/// 36 joint coordinates must be set. Throws pkm::IoError "FILE:LINE: message" on malformed lines,
/// non-finite values and unusable geometry.
[[nodiscard]] HexapodMachine readLinuxcncHal(const std::string& hal_path,
                                             const HalReadOptions& options = {});

/// readLinuxcncHal of a HAL file held in memory (its name is the path messages and the machine's
/// source use) and, when given, its INI, also in memory; no INI is looked for. Throws as
/// readLinuxcncHal.
[[nodiscard]] HexapodMachine parseLinuxcncHal(const NamedText& hal,
                                              const std::optional<NamedText>& ini = std::nullopt);

/// Applies an INI file's [TRAJ] HOME, [TRAJ] LINEAR_UNITS and [JOINT_0..5] MIN_LIMIT/MAX_LIMIT to
/// `machine`. Throws pkm::IoError "FILE:LINE: message".
void applyLinuxcncIni(const std::string& ini_path, HexapodMachine& machine);
/// applyLinuxcncIni of an INI held in memory (messages use its name).
void applyLinuxcncIni(const NamedText& ini, HexapodMachine& machine);

/// The genhexkins `setp` block for `machine`: joints with the TCP offset folded into the platform
/// points, spindle-offset, tool-offset (when not 0), convergence-criterion, limit-iterations, and
/// the
/// `# pkm: units/home` lines (so the output loads on its own), and the INI values (HOME, joint
/// HOME_OFFSET and limits) as comments. LinuxCNC joint positions are full
/// joint-centre distances, so struts with a length offset get a comment saying so.
[[nodiscard]] std::string writeLinuxcncSetp(const HexapodMachine& machine);

/// The `setp pkmhexkins.*` block of `machine` for pkm's LinuxCNC kinematics component pkmhexkins
/// (docs/linuxcnc.md, "The pkmhexkins kinematics component"), pins mapped one to one from the
/// model: `base.N.x|y|z` (world frame), `platform.N.x|y|z` (platform frame, not folded with the
/// tool point), `length-offset.N`, `tool.x|y|z` (the controlled point), `spindle-offset`,
/// `home.x … home.c` (the second forward-kinematics seed, degrees), `convergence-criterion` and
/// `limit-iterations`; lengths in the machine's unit, numbers in shortest round-trip form. The
/// INI values that go with it are comments: pkmhexkins' joint positions are the strut readings,
/// so [JOINT_n] HOME = HOME_OFFSET = the reading at the home pose and MIN_LIMIT/MAX_LIMIT = the
/// stroke. It does not load the module nor net `tool-offset` (see pkmhexkinsJointValues).
[[nodiscard]] std::string writePkmhexkinsSetp(const HexapodMachine& machine);

/// A pkmhexkins joint's INI values: HOME = HOME_OFFSET = the strut reading at the machine's home
/// pose; MIN_LIMIT/MAX_LIMIT = the stroke (none where it is unbounded). Machine length unit.
struct PkmhexkinsJointValues {
  double home = 0.0;
  std::optional<double> min_limit, max_limit;
};

/// The six joints' pkmhexkins INI values of `machine` (inverse kinematics at model.home).
[[nodiscard]] std::array<PkmhexkinsJointValues, 6> pkmhexkinsJointValues(
    const HexapodMachine& machine);

}  // namespace pkm::io
