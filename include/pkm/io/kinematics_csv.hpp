/// @file
/// @brief The CSV rows of the limit checks and of the dependent rotational motion
/// (`pkm hexapod check`, `pkm exechon check`, `pkm exechon drm`; docs/formats.md). Lengths in the
/// machine unit, angles in degrees; an empty field is a limit that is disabled (infinite margin).
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "pkm/kinematics/exechon_checks.hpp"
#include "pkm/kinematics/exechon_drm.hpp"
#include "pkm/kinematics/hexapod_checks.hpp"

namespace pkm::io {

/// The header of `pkm hexapod check`, with its newline.
[[nodiscard]] std::string hexapodCheckCsvHeader();

/// Appends row `index` of `pkm hexapod check`: the status, the smallest stroke, base-joint and
/// platform-joint margins with the strut or joint they belong to, the closest legs and their
/// interference margin, the scaled condition number and its margin, and the violations
/// ("KIND ITEM value=V limit=L", joined by "; ").
void appendHexapodCheckRow(std::string& out,
                           std::size_t index,
                           const kinematics::HexapodCheckResult& check);

/// The header of `pkm exechon check`, with its newline.
[[nodiscard]] std::string exechonCheckCsvHeader();

/// Appends row `index` of `pkm exechon check` with `status` (check.status() or "axis_limit"):
/// the smallest leg-stroke margin and its leg (A, B, C), the α, β, C, A margins, whether the
/// wrist is at its pole, the condition number and its margin, and the violations; only the
/// status when the solve failed.
void appendExechonCheckRow(std::string& out,
                           std::size_t index,
                           std::string_view status,
                           const kinematics::ExechonCheckResult& check);

/// The table of `pkm exechon drm`: θ, φ_DRM, the 5th-order fit and its residual per sample
/// (degrees), "# status", then either "# failed at point N" (no fit) or the fit's coefficients
/// c0..c5 (rad, Lee et al. 2019, eq. 10), max |φ_DRM| and the largest fit deviation.
[[nodiscard]] std::string drmCircleCsv(const kinematics::DrmCircleResult& result);

}  // namespace pkm::io
