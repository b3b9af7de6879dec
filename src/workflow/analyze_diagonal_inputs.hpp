// Internal: the readers of `pkm analyze diagonals` (workflow/analyze_diagonals.hpp): simulator line
// files identified as body diagonals, and the body, step and shifted tables.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string_view>
#include <vector>

#include "pkm/io/named_text.hpp"
#include "pkm/io/text_table.hpp"
#include "pkm/metrology/body_diagonals.hpp"
#include "pkm/metrology/shifted_diagonal.hpp"
#include "pkm/metrology/step_diagonal.hpp"

namespace pkm::workflow::detail {

inline constexpr double kCornerTolerance = 1e-3;     ///< mm: a line start that is a box corner
inline constexpr double kDirectionTolerance = 1e-6;  ///< a line direction that is a diagonal's

/// "(a, b, c)" from a measurement file's metadata; throws pkm::IoError when it is not 3 numbers.
[[nodiscard]] std::optional<Eigen::Vector3d> metaVector(const io::TextTable& t,
                                                        std::string_view key);

/// A measurement file (`pkm simulate`): target, run, direction, reading and the line metadata.
struct LineFile {
  Eigen::Vector3d start, direction;
  std::vector<double> target, deviation;
  std::vector<int> run, dir, sub_step;
};

/// True for a simulator line file (target and reading columns, no diagonal column).
[[nodiscard]] bool isLineFile(const io::TextTable& t);
/// Reads a line file; deviation = reading − target. Throws pkm::IoError "NAME:LINE: message".
[[nodiscard]] LineFile readLineFile(const io::TextTable& t);

/// The body diagonal whose start corner is `start` (or nullopt).
[[nodiscard]] std::optional<metrology::BodyDiagonal> diagonalAt(const Eigen::Vector3d& start,
                                                                const Eigen::Vector3d& size);

/// The body diagonal named in field (row, col): PPP, NPP, PNP or NNP; throws pkm::IoError.
[[nodiscard]] metrology::BodyDiagonal diagonalField(const io::TextTable& t,
                                                    std::size_t row,
                                                    std::size_t col);

/// Body-diagonal samples; rows without runs are numbered per (diagonal, position, direction).
[[nodiscard]] std::vector<metrology::BodyDiagonalSample> readBodySamples(
    const std::vector<io::NamedText>& data, const Eigen::Vector3d& size);

/// Step-diagonal passes: consecutive rows of one (diagonal, run, direction); sub_step 1 opens a
/// step, sub-steps 1, 2, 3 in order.
[[nodiscard]] std::vector<metrology::StepDiagonalPass> readStepPasses(
    const std::vector<io::NamedText>& data, const Eigen::Vector3d& size);

/// Shifted-diagonal measurements; a line file's length error is the mean deviation at its last
/// target minus that at its first (metrology::perTargetMeans).
[[nodiscard]] std::vector<metrology::ShiftedDiagonalMeasurement> readShiftedMeasurements(
    const std::vector<io::NamedText>& data, const Eigen::Vector3d& size);

}  // namespace pkm::workflow::detail
