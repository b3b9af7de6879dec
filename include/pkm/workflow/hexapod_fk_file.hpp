/// @file
/// @brief `pkm hexapod fk` as a workflow (docs/formats.md "hexapod fk"): strut readings from a CSV
/// (l0..l5) solved in order — each row seeds the next, as in a servo loop — with the input read
/// a chunk ahead and the poses formatted on a second thread, so that reading, solving and
/// printing overlap; the rows' CSV text reaches the caller in order.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "pkm/io/hexapod_machine.hpp"
#include "pkm/kinematics/pose_rpy.hpp"

namespace pkm::workflow {

/// The readings to solve and how.
struct HexapodFkFileRequest {
  std::string lengths;  ///< CSV of strut readings, columns l0..l5 ("-": standard input)
  /// The first row's seed (default: the machine's home pose): the machine's unit and radians.
  std::optional<kinematics::PoseRpy> seed;
  /// Every row from `seed` (or home) instead of from the previous row's pose.
  bool from_seed = false;
};

/// What a run solved.
struct HexapodFkFileSummary {
  std::size_t rows = 0;    ///< rows solved
  std::size_t failed = 0;  ///< rows without a pose (their status says why)
};

/// The header line of the output, "x,y,z,a,b,c,iterations,status\n".
inline constexpr std::string_view kHexapodFkHeader = "x,y,z,a,b,c,iterations,status\n";

/// Solves every row of request.lengths on `machine` and hands the output CSV (kHexapodFkHeader,
/// then one row per input row: x, y, z in the machine's unit, a, b, c in degrees, the iterations
/// and the status; no pose on a failed row) to `write`, in order, in pieces, from a second
/// thread (placed on another CPU when there are two). A bad input line throws pkm::IoError
/// "FILE:LINE: ..." after the rows before it were written; an exception of `write` ends the run
/// and is rethrown.
HexapodFkFileSummary solveHexapodFkFile(const io::HexapodMachine& machine,
                                        const HexapodFkFileRequest& request,
                                        const std::function<void(std::string_view)>& write);

}  // namespace pkm::workflow
