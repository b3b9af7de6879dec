/// @file
/// @brief `pkm linuxcnc install` as a workflow (docs/linuxcnc.md, "pkm linuxcnc install"): a
/// calibrated hexapod written into an existing LinuxCNC configuration in place — the genhexkins
/// values of the HAL file the INI loads and the INI's joint home and limits
/// (io/linuxcnc_patch.hpp) — with the differences shown, a backup of each file changed, and
/// nothing written without `force`.
#pragma once

#include <string>
#include <vector>

#include "pkm/io/linuxcnc_patch.hpp"

namespace pkm::workflow {

/// A LinuxCNC install request.
struct LinuxcncInstallRequest {
  std::string calibration;  ///< the calibrated hexapod (CAL.json of `pkm calibrate hexapod`)
  std::string ini;          ///< the configuration's INI file (required)
  bool force = false;       ///< write the changes (else only report them)
  /// Throws pkm::InvalidArgument naming the option when calibration or ini is empty.
  void validate() const;
};

/// What an install changed (or would change).
struct LinuxcncInstallResult {
  /// "genhexkins" (the HAL file, then the INI) or "pkmhexkins" (its parameter file).
  std::string kinematics = "genhexkins";
  std::vector<io::TextPatch> patches;  ///< the files changed, in that order
  std::string diff;                    ///< the unified diff of both ("" : nothing to change)
  bool written = false;                ///< the files were patched (force, and something changed)
  std::vector<std::string> backups;    ///< the copies of the files as they were
};

/// For a configuration whose [KINS] loads pkmhexkins with a parameter file, replaces that file
/// (io::patchPkmhexkinsParameters; the INI is kept). Otherwise finds the HAL file with genhexkins
/// `setp` lines among the INI's [HAL] HALFILE entries (relative to the INI's folder), patches it
/// and the INI. Then with `force` backs each changed file up as
/// FILE.pkm-backup (FILE.pkm-backup.1, … when that exists: a backup is never overwritten) and
/// writes it atomically. Throws pkm::IoError for unreadable files, a configuration with neither,
/// units that differ or missing lines (io::patchKinematicsHal, io::patchHexapodIni),
/// pkm::InvalidArgument for a calibration that is not a hexapod.
[[nodiscard]] LinuxcncInstallResult installIntoLinuxcnc(const LinuxcncInstallRequest& request);

}  // namespace pkm::workflow
