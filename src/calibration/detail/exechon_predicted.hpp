/// @file
/// @brief Internal: an Exechon calibration's data as its estimate predicts them, the starting
/// point of the Monte Carlo propagations (monteCarloExechon, exechonBudgetMonteCarlo).
#pragma once

#include <optional>

#include "pkm/calibration/exechon_calibration.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/kinematics/exechon_fk.hpp"

namespace pkm::calibration::detail {

/// `data` with every point (and direction) replaced by what `estimate` predicts for its joints in
/// the measurement frame `frame` (world when empty); observations without a converging FK are
/// dropped.
[[nodiscard]] ExechonCalibrationData predictedExechonData(
    const kinematics::ExechonModel& estimate,
    const ExechonCalibrationData& data,
    const std::optional<geometry::RigidTransform>& frame,
    const kinematics::FkOptions& fk);

}  // namespace pkm::calibration::detail
