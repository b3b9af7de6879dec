/// @file
/// @brief LinuxCNC joint compensation files ([JOINT_n] COMP_FILE, COMP_FILE_TYPE 0 or 1): writer,
/// strict reader and a model of how LinuxCNC's motion controller applies them (LinuxCNC
/// documentation docs/src/config/ini-config.adoc, [JOINT_n] COMP_FILE; LinuxCNC sources
/// src/emc/motion/usrmotintf.cc and control.c; the sample configs' screwcompX.dat;
/// docs/compensation.md).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "pkm/compensation/axis_table.hpp"

namespace pkm::compensation {

/// EMCMOT_COMP_SIZE (src/emc/motion/motion.h): the most rows LinuxCNC loads per joint.
inline constexpr std::size_t kLinuxcncMaxRows = 256;

/// A LinuxCNC compensation file as written: one row `nominal second third` per line, whitespace
/// separated, machine units (mm here), no header or comment lines (usrmotLoadComp stops at the
/// first line that is not three numbers), nominal strictly increasing (command.c: "compensation
/// values must increase"), at most 256 rows.
/// - type 0: second/third = the ACTUAL position reached when commanded to nominal while moving in
///   + / −; LinuxCNC turns them into trims nominal − actual.
/// - type 1: second/third = the TRIM added to the command while moving in + / −.
struct LinuxcncCompFile {
  int type = 1;                 ///< COMP_FILE_TYPE, 0 or 1
  std::vector<double> nominal;  ///< commanded joint positions, strictly increasing
  std::vector<double> forward;  ///< second column (moving +)
  std::vector<double> reverse;  ///< third column (moving −)
  /// Throws pkm::InvalidArgument unless type is 0 or 1, 1 ≤ rows ≤ 256, sizes are equal, values
  /// finite and nominal strictly increasing.
  void validate() const;
  /// The trim (correction added to the command) of row i when moving in `direction` (+1/−1):
  /// type 1 the stored value, type 0 nominal − actual (usrmotintf.cc).
  [[nodiscard]] double trim(std::size_t i, int direction) const;
};

/// The file for `table` (LinuxCNC ini-config.adoc, COMP_FILE_TYPE; per target P_i):
///   type 0: `P_i  P_i + x̄i↑  P_i + x̄i↓`;   type 1: `P_i  −x̄i↑  −x̄i↓`.
/// Numbers in shortest round-trip form. Tables with more than 256 rows must be resampled first
/// (fitToTarget). Throws pkm::InvalidArgument for an invalid table, a type other than 0/1 or more
/// than 256 rows.
[[nodiscard]] LinuxcncCompFile linuxcncCompFromTable(const AxisErrorTable& table, int type);
/// The text of `file`: one line `nominal second third\n` per row. Throws as validate().
[[nodiscard]] std::string writeLinuxcncComp(const LinuxcncCompFile& file);

/// Parses a compensation file of COMP_FILE_TYPE `type`. Stricter than LinuxCNC, which silently
/// stops at the first bad line: every line must hold exactly three finite numbers (blank lines
/// only at the end), nominal strictly increasing, 1..256 rows. Throws pkm::IoError
/// "SOURCE:LINE: message" for a bad line, "SOURCE: message" for an empty file or too many rows;
/// pkm::InvalidArgument for a type other than 0/1.
[[nodiscard]] LinuxcncCompFile parseLinuxcncComp(const std::string& text,
                                                 const std::string& source,
                                                 int type);
/// Reads and parses `path`; throws pkm::IoError when it cannot be read, or as parseLinuxcncComp.
[[nodiscard]] LinuxcncCompFile readLinuxcncComp(const std::string& path, int type);

/// The motor (joint) position command LinuxCNC produces for commanded joint position `commanded`
/// while moving in `direction` (+1 / −1: the sign of the commanded velocity; LinuxCNC keeps the
/// last one while stopped): commanded + trim, the trim linearly interpolated in the commanded
/// position between the two enclosing rows and held at the end rows' values outside
/// (src/emc/motion/control.c; the backlash_filt ramp towards it is not modelled: steady state).
/// Throws pkm::InvalidArgument for a non-finite position or a direction other than ±1.
[[nodiscard]] double applyLinuxcncComp(const LinuxcncCompFile& file,
                                       double commanded,
                                       int direction);

}  // namespace pkm::compensation
