/// @file
/// @brief Abbe error removal: a linear or straightness reading taken at an offset from the point of
/// interest is corrected by offset × angle from measured angular errors (MXT700S parallelism paper,
/// §4: "the Abbe errors in all measurement data were computed from the measured angular errors and
/// the Abbe offsets and removed"; first-order rigid-body model with ISO 230-1 error names).
#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

#include "pkm/geometry/error_table.hpp"

namespace pkm::metrology {

/// A measured angular error of the moving axis: the rotation (rad, right-handed) about the unit
/// work-frame axis `axis` as a function of the axis position (one-column table).
struct AngularProfile {
  geometry::ErrorTable1d table;                     ///< angle, rad, vs axis position
  Eigen::Vector3d axis = Eigen::Vector3d::UnitY();  ///< rotation axis (normalised internally)
};

/// First-order Abbe error of a reading along unit `direction` taken at `offset` from the point of
/// interest (both work frame, offset in the length unit) when the moving part is rotated by the
/// small rotation vector `rotation` (rad): direction · (rotation × offset).
/// Throws pkm::InvalidArgument for non-finite input or a zero direction.
[[nodiscard]] double abbeError(const Eigen::Vector3d& rotation,
                               const Eigen::Vector3d& offset,
                               const Eigen::Vector3d& direction);

/// Readings at the point of interest: reading_k - direction · ((ε(x_k) - ε(datum)) × offset), ε the
/// sum of the angular profiles (angles relative to `datum`, where the instrument was zeroed).
/// Throws pkm::InvalidArgument for sizes that differ, non-finite values, a zero axis or direction,
/// and as ErrorTable1d::evaluate.
[[nodiscard]] std::vector<double> removeAbbeError(std::span<const double> positions,
                                                  std::span<const double> readings,
                                                  std::span<const AngularProfile> angles,
                                                  const Eigen::Vector3d& offset,
                                                  const Eigen::Vector3d& direction,
                                                  double datum);

}  // namespace pkm::metrology
