/// @file
/// @brief `pkm volumetric` as a workflow (docs/formats.md): the volumetric error Δp of a hybrid
/// machine (X2/Y2 axes carrying an Exechon PKM; MXT700S parallelism paper, eq. 3) from its
/// geometric errors, exact and first-order, over a grid of tool positions or a list of axis
/// commands. Rows are handed to a sink as they are computed, so a large grid streams in constant
/// memory.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "pkm/io/machine_loader.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/io/volumetric_csv.hpp"
#include "pkm/workflow/progress.hpp"

namespace pkm::workflow {

/// A volumetric-error request: either a grid or a list of commands.
struct VolumetricRequest {
  std::string machine = io::kDefaultExechonMachine;  ///< Exechon file or name with "hybrid"
  std::string errors;  ///< geometric errors: a JSON file or a built-in name (required)
  /// "X0:X1:NX,Y0:Y1:NY,Z0:Z1:NZ": tool positions in the work frame, machine unit, x fastest
  /// (NX points from X0 to X1; 1 point: X0 alone).
  std::optional<std::string> grid;
  /// CSV with header x2,y2,xp,yp,zp (axis commands), when there is no grid.
  std::optional<io::NamedText> commands;
  /// With a grid: the X2 and Y2 positions (both or neither; default the centred split,
  /// kinematics::hybridCommandCentred).
  std::optional<double> x2, y2;
  /// Throws pkm::IoError for neither or both of grid and commands, only one of x2 and y2, or a
  /// grid that does not parse ("--grid '...': ...").
  void validate() const;
};

/// The axis values of a grid "X0:X1:NX,Y0:Y1:NY,Z0:Z1:NZ" (NX in [1, 10000], at most 10 million
/// points). Throws pkm::IoError "--grid 'TEXT': ..." naming what is wrong.
[[nodiscard]] std::array<std::vector<double>, 3> parseVolumetricGrid(const std::string& text);

/// Where the rows go: `begin` once every input is checked, then `row` for each command in order.
/// Either may be empty.
struct VolumetricSink {
  std::function<void()> begin;
  std::function<void(const io::VolumetricRow&)> row;
};

/// Computes the volumetric error at every grid point or command (kinematics::hybridVolumetricError
/// and hybridVolumetricErrorLinear) and returns the number of rows. Notices: the machine reader's
/// notes. Cancellation is checked every 4096 rows. Throws pkm::IoError for a machine without a
/// "hybrid" section, errors in another unit than the machine, a bad request or a bad commands
/// file ("NAME:LINE: message"; the rows before it have been handed over).
std::size_t computeVolumetricErrors(const VolumetricRequest& request,
                                    const VolumetricSink& sink,
                                    const RunControl& control = {});

}  // namespace pkm::workflow
