/// @file
/// @brief The tracker-frame registration of the calibration workflows (calibrate_hexapod.cpp,
/// calibrate_exechon_tripod.cpp): `--registration FILE` read, fitted and checked
/// (docs/calibration.md, "Frames").
#pragma once

#include <optional>
#include <string>

#include "pkm/calibration/frame_registration.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"

namespace pkm::workflow::detail {

/// Where a calibration's world frame comes from: "machine" (world-frame readings), "registered"
/// (tracker-frame readings and a registration), "unregistered" (tracker-frame readings only).
[[nodiscard]] std::string worldFrameKind(bool tracker_frame, bool registered);

/// The registration of `file` (io::parseRegistrationCsv; coordinates in `unit`, the tracker
/// files' unit): the rigid fit of the nests' table coordinates to the tracker's readings, the
/// stated σ floor from the tracker of `sources` (±(a + b·L) rectangular at the longest nest
/// range). Throws pkm::IoError "FILE:LINE" for a malformed file, pkm::InvalidArgument when the
/// nests lie on one line or do not fit a rigid motion (the largest residual above
/// calibration::kAcceptableResidualFraction × `characteristic_length`: a nest's coordinates or
/// reading mistyped, nests in another order, another unit), naming the worst nest and its line.
[[nodiscard]] calibration::FrameRegistration registerTrackerFrame(
    const io::NamedText& file,
    LengthUnit unit,
    double characteristic_length,
    const metrology::UncertaintySources& sources);

/// Refuses (pkm::InvalidArgument) a registration for readings already in the machine's frame.
void refuseRegistrationOfWorldData(const std::optional<io::NamedText>& registration,
                                   bool tracker_frame);

}  // namespace pkm::workflow::detail
