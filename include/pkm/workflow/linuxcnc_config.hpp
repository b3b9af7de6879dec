/// @file
/// @brief `pkm linuxcnc config` as a workflow (docs/linuxcnc.md, "From `pkm linuxcnc config` to a
/// running machine"): a complete, runnable LinuxCNC configuration folder for a hexapod
/// (pkmhexkins) or an Exechon (pkmexechonkins) on LinuxCNC's simulator, from a machine spec as
/// `--machine` takes it, with joint compensation tables (COMP_FILE) when given. The files are
/// io/linuxcnc_config.hpp's; this reads the inputs and writes the folder, refusing to replace a
/// file without `force`.
#pragma once

#include <array>
#include <span>
#include <string>
#include <vector>

#include "pkm/compensation/linuxcnc_comp.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/metrology/iso230_2.hpp"

namespace pkm::workflow {

/// A joint compensation table to include (`--comp-file JOINT=FILE`).
struct LinuxcncCompInput {
  int joint = 0;     ///< the joint it corrects (hexapod 0–5 = struts, Exechon 0–4)
  std::string path;  ///< the table written by `pkm compensate table --format linuxcnc0|linuxcnc1`
};

/// A `pkm linuxcnc config` request.
struct LinuxcncConfigRequest {
  /// The machine: a hexapod JSON file (also CAL.json of `pkm calibrate hexapod`), a LinuxCNC
  /// genhexkins `.hal` file, an Exechon JSON file, or a built-in name ("default" = the default
  /// hexapod).
  std::string machine = "default";
  std::string ini;  ///< the INI of a `.hal` machine ("" : found beside it)
  std::string out;  ///< the configuration folder (created when missing)
  std::vector<LinuxcncCompInput> comp_files;  ///< copied as jointN.comp, referenced by the INI
  /// The ISO 230-2 positioning data a table was made from (`--comp-data JOINT=FILE`, mm): the
  /// table's corrections must oppose its errors (checkCompSign).
  std::vector<LinuxcncCompInput> comp_data;
  int comp_file_type = -1;       ///< COMP_FILE_TYPE of every table: 0 or 1 (required with them)
  std::string display = "axis";  ///< [DISPLAY] DISPLAY ("linuxcncrsh" for a headless machine)
  bool force = false;            ///< replace files of the same names in `out`
  /// Refuse tables with implausible corrections (checkCompPlausible); false = `--no-comp-check`.
  bool check_comp_files = true;
  /// A hexapod truth.json (`pkm simulate`; `--simulate-truth`): the configuration gets the
  /// simulated physical machine in its loop, copied as truth.json with truth.hal
  /// (io::linuxcncTruthHal). "" : none. Hexapods in mm only.
  std::string simulate_truth;
  /// The pkm-truth program truth.hal starts (an absolute path, or a name on LinuxCNC's PATH).
  std::string truth_program = "pkm-truth";
  /// Throws pkm::InvalidArgument naming the option: empty machine or out, tables without a
  /// type 0 or 1, comp_data for a joint without a table.
  void validate() const;
};

/// The largest correction a compensation table may apply, as a fraction of the joint's travel.
inline constexpr double kCompMaxFractionOfTravel = 0.01;

/// Refuses a joint compensation table whose corrections (compensation::LinuxcncCompFile::trim,
/// as its declared COMP_FILE_TYPE reads them) exceed kCompMaxFractionOfTravel of the joint's
/// travel: the span of the table's nominal positions, or `range` (the joint's [min, max], ±inf
/// for an open side) for a one-row table. A type 0 table (nominal, actual positions) declared as
/// type 1 has corrections of the size of the positions, a type 1 table (trims) declared as type 0
/// of the size of the positions too: when the other type would be plausible the message says so.
/// Throws pkm::InvalidArgument "SOURCE:LINE: ..." naming the first implausible row, `joint` and
/// `--no-comp-check`. A table without a known travel passes. A flipped sign cannot be seen in a
/// table alone: checkCompSign compares it with the errors it was made from.
void checkCompPlausible(const compensation::LinuxcncCompFile& file,
                        const std::string& source,
                        int joint,
                        std::array<double, 2> range);

/// Refuses a table whose corrections have the sign of the errors it should cancel: over the
/// samples of `errors` (the positioning data the table was made from, in the table's unit), the
/// table's correction (compensation::applyLinuxcncComp − position) against the correction that
/// cancels each error, −(measured − target), must not correlate negatively (a flipped table doubles
/// the error; docs/linuxcnc.md, "COMP_FILE tables in LinuxCNC"). Throws pkm::InvalidArgument
/// "SOURCE:1: ..." naming `joint`, `errors_source` and `--no-comp-check`.
void checkCompSign(const compensation::LinuxcncCompFile& file,
                   const std::string& source,
                   int joint,
                   std::span<const metrology::PositioningSample> errors,
                   const std::string& errors_source);

/// What a request produced.
struct LinuxcncConfigResult {
  std::string kind;                  ///< "hexapod" or "exechon"
  std::string ini;                   ///< the INI's path (run `linuxcnc INI`)
  std::vector<std::string> files;    ///< every path written, the INI first
  std::vector<std::string> notices;  ///< what the machine reader assumed
};

/// The configuration's files (names inside the folder and texts) without writing anything; the
/// compensation tables are read and checked (compensation::parseLinuxcncComp, and
/// checkCompPlausible against the joint's range unless request.check_comp_files is false) and
/// included as `jointN.comp`. `notices` receives the machine reader's notices. Throws pkm::IoError
/// for an unreadable or malformed machine or table (FILE:LINE), pkm::InvalidArgument as
/// request.validate() and the io::hexapodLinuxcncConfig / io::exechonLinuxcncConfig checks.
[[nodiscard]] std::vector<io::NamedText> linuxcncConfigFiles(const LinuxcncConfigRequest& request,
                                                             std::vector<std::string>& notices);

/// Writes linuxcncConfigFiles into request.out (each file atomically). Without `force`, nothing is
/// written when one of the files exists: throws pkm::InvalidArgument "PATH exists; pass --force
/// to replace it (nothing was written)". Other files in the folder are never touched. Throws as
/// linuxcncConfigFiles, and pkm::IoError when the folder or a file cannot be written.
[[nodiscard]] LinuxcncConfigResult writeLinuxcncConfig(const LinuxcncConfigRequest& request);

}  // namespace pkm::workflow
