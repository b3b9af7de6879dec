/// @file
/// @brief A complete LinuxCNC configuration for a pkm machine, as text files (docs/linuxcnc.md,
/// "From `pkm linuxcnc config` to a running machine"): the INI, the kinematics HAL file (pkm's
/// components pkmhexkins or pkmexechonkins), a simulator HAL file (motion with the joints looped
/// back), a tool table and, for an Exechon, the component's parameter file. World coordinates are
/// the ones `pkm hexapod fk` / `pkm exechon fk` report for the machine, in its length unit; the
/// joints' HOME is the exact inverse kinematics at the machine's home, so that after homing
/// LinuxCNC stands at that pose. The workflow (workflow/linuxcnc_config.hpp) writes them.
#pragma once

#include <string>
#include <vector>

#include "pkm/io/exechon_machine.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "pkm/io/named_text.hpp"

namespace pkm::io {

/// A joint compensation table the INI references ([JOINT_n] COMP_FILE, COMP_FILE_TYPE).
struct LinuxcncCompReference {
  int joint = 0;     ///< joint index (hexapod 0–5, Exechon 0–4)
  std::string file;  ///< the file name inside the configuration folder
  int type = 1;      ///< COMP_FILE_TYPE: 0 (actual positions) or 1 (trims), docs/compensation.md
};

/// What the configuration holds besides the machine.
struct LinuxcncConfigOptions {
  /// [DISPLAY] DISPLAY: "axis" (LinuxCNC's GUI) or "linuxcncrsh" (headless, telnet port 5007),
  /// or any other display program LinuxCNC knows. A word of [A-Za-z0-9_.-].
  std::string display = "axis";
  std::vector<LinuxcncCompReference> comp_files;  ///< at most one per joint
  /// More HAL files for the INI's [HAL] section, after the kinematics and simulator files (file
  /// names inside the configuration folder), e.g. linuxcncTruthHal's "truth.hal".
  std::vector<std::string> extra_hal_files;
  /// Throws pkm::InvalidArgument naming the field: an empty or malformed display, a joint index
  /// outside 0..joints-1 or given twice, an empty or path-like file name, a type other than 0/1.
  void validate(int joints) const;
};

/// The HAL file of the simulated physical machine in the loop (docs/linuxcnc.md, "A simulated
/// machine in the loop"): `loadusr -Wn pkmtruth PROGRAM --truth TRUTH --name pkmtruth
/// --joint-offset O0,..` (the userspace component apps/pkm-truth) and each joint's motor command
/// (the simulator's signals jN-pos: LinuxCNC's command to the drive, with its backlash and
/// COMP_FILE corrections) into pkmtruth.joint-N; a strut's reading is its motor position plus the
/// joint's HOME_OFFSET, `joint_offsets` (one per joint). `program` and `truth` are written as
/// given (a truth name is relative to the configuration folder); neither may hold whitespace or
/// '#'. Throws pkm::InvalidArgument otherwise.
[[nodiscard]] std::string linuxcncTruthHal(const std::string& program,
                                           const std::string& truth,
                                           const std::vector<double>& joint_offsets);

/// The file names of a configuration (inside its folder), the INI first.
struct LinuxcncConfigNames {
  std::string ini;         ///< "<machine name>.ini", the name reduced to [A-Za-z0-9_.-]
  std::string kinematics;  ///< "kinematics.hal"
  std::string sim;         ///< "sim.hal"
  std::string tool_table;  ///< "tool.tbl"
  std::string params;      ///< "<machine name>.params", the kinematics' parameter file
};

/// The names the configuration of a machine called `machine_name` uses.
[[nodiscard]] LinuxcncConfigNames linuxcncConfigNames(const std::string& machine_name);

/// The configuration of a hexapod with pkmhexkins: the parameter file linuxcncHexapodParameters
/// writes (the 42 geometry parameters, tool point, spindle offset, home and solver settings),
/// loaded by `[KINS] KINEMATICS = pkmhexkins params=NAME.params` (read and checked at load, a
/// name relative to the configuration folder); 6 LINEAR joints, the strut
/// readings, with HOME = HOME_OFFSET = the reading at the home pose and MIN/MAX_LIMIT = the stroke;
/// world X Y Z A B C (degrees), [TRAJ] HOME = the home pose; the axis limits are how far the
/// machine reaches along each world coordinate from home within every limit `pkm hexapod check`
/// applies (stroke, joint cones, interference, conditioning) with every platform joint at least
/// kinematics::kMirrorClearanceFraction characteristic lengths (at most half its home height) above
/// the base plane (kinematics/hexapod_clearance.hpp: never the singular plane or the mirror
/// assembly beyond it), rounded towards home; then, unless every one of the 64 corners of that box
/// passes the same test, all six ranges shrunk by a common fraction until they do (a line in
/// `notices` says so when it is given). Velocities and
/// accelerations: the machine's joint_rates, else `pkm gcode run`'s defaults (200 unit/s,
/// 2000 unit/s²); a rotation's rate is the joint rate over the characteristic length. Files in the
/// order of LinuxcncConfigNames. Throws pkm::InvalidArgument naming the machine's source when the
/// home pose puts a strut outside its stroke or a platform joint on or below the base plane, and as
/// options.validate(6).
[[nodiscard]] std::vector<NamedText> hexapodLinuxcncConfig(
    const HexapodMachine& machine,
    const LinuxcncConfigOptions& options,
    std::vector<std::string>* notices = nullptr);

/// The configuration of an Exechon with pkmexechonkins (docs/linuxcnc.md, "Exechon kinematics in
/// LinuxCNC"): the parameter file linuxcncExechonParameters writes, loaded by
/// `[KINS] KINEMATICS = pkmexechonkins params=NAME.params` (a name relative to the configuration
/// folder, where LinuxCNC runs); joints 0–2 the leg readings (LINEAR), 3 wrist C and 4 wrist A
/// (ANGULAR, degrees); world X Y Z (the tool point, `pkm exechon fk`'s x,y,z) A C (the wrist
/// readings). HOME = HOME_OFFSET = the home configuration's joints; MIN/MAX_LIMIT = the legs'
/// strokes and the wrist's C and A ranges (±1e9 for an open side); X Y Z limits: the reach along
/// each coordinate from home with the wrist held (strokes, alpha/beta ranges, conditioning),
/// rounded towards home; A and C: the wrist ranges. Rates: joint_rates (legs; wrist in deg/s),
/// else `pkm gcode run`'s defaults. A hybrid machine's X2/Y2 are not part of it. Throws
/// pkm::InvalidArgument as options.validate(5) and when the home is outside a limit.
[[nodiscard]] std::vector<NamedText> exechonLinuxcncConfig(const ExechonMachine& machine,
                                                           const LinuxcncConfigOptions& options);

}  // namespace pkm::io
