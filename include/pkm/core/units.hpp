/// @file
/// @brief Length units of machine files and angle conversions at file and CLI boundaries.
#pragma once

#include <numbers>
#include <optional>
#include <string_view>

namespace pkm {

/// The length unit a machine file declares; every length in and out of that machine uses it.
enum class LengthUnit { kMillimetre, kInch };

/// "mm" or "inch".
[[nodiscard]] std::string_view toString(LengthUnit unit);
/// Parses "mm" or "inch" (also "in"); std::nullopt for anything else.
[[nodiscard]] std::optional<LengthUnit> lengthUnitFromString(std::string_view text);
/// Millimetres per one `unit` (1 or 25.4).
[[nodiscard]] constexpr double millimetresPer(LengthUnit unit) {
  return unit == LengthUnit::kInch ? 25.4 : 1.0;
}

/// Degrees to radians.
[[nodiscard]] constexpr double degToRad(double deg) { return deg * (std::numbers::pi / 180.0); }
/// Radians to degrees.
[[nodiscard]] constexpr double radToDeg(double rad) { return rad * (180.0 / std::numbers::pi); }
/// Microradians per radian (angular readings in measurement files are in µrad).
inline constexpr double kUradPerRad = 1e6;

}  // namespace pkm
