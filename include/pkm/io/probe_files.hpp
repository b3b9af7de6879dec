/// @file
/// @brief Touch-probe files (docs/formats.md, "Touch-probe files"): the spindle-reversal touches
/// on a master ring that `pkm analyze probe-offset` reads, and the circle measurements (without
/// and with DRM compensation) that `pkm analyze circle` reads (Lee et al. 2019).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "pkm/io/text_table.hpp"
#include "pkm/simulation/touch_probe.hpp"

namespace pkm::io {

/// The offset file: metadata lines, then the header `touch,run,spindle_deg,drm_deg,x,y,z` and one
/// row per touch: label (+x, -x, +y, -y), run, commanded spindle angle and φ_DRM about the tool
/// direction (degrees), the spindle-axis position at the trigger (mm).
[[nodiscard]] std::string probeOffsetCsv(const Metadata& metadata,
                                         const std::vector<simulation::TouchRecord>& touches);

/// A circle file: metadata lines, then the header
/// `x,y,run,approach_deg,spindle_deg,drm_deg,spindle_x,spindle_y,z`: x, y the surface point the
/// OMM reports with the calibrated offset (simulation::reportedSurfacePoint), mm; then the run, the
/// approach direction, spindle and DRM angles (degrees) and the spindle-axis position (mm).
[[nodiscard]] std::string probeCircleCsv(const Metadata& metadata,
                                         const simulation::TouchProbeSetup& setup,
                                         const std::vector<simulation::TouchRecord>& touches);

/// The three files `pkm simulate` writes for a touch-probe measurement, {file name, text}:
/// NAME_offset.csv, NAME_circle_uncompensated.csv, NAME_circle_compensated.csv.
[[nodiscard]] std::vector<std::pair<std::string, std::string>> touchProbeFiles(
    const std::string& scenario,
    std::uint64_t seed,
    const simulation::TouchProbeSetup& setup,
    const simulation::TouchProbeResult& result);

}  // namespace pkm::io
