/// @file
/// @brief Arc centres of G2/G3 in the active plane as LinuxCNC 2.9 computes them (G-code
/// reference "G2, G3 Arc Move": centre format with I J K offsets, radius format with R, and the
/// start/end radius check with the tolerances of the INI reference, [RS274NGC]
/// CENTER_ARC_RADIUS_TOLERANCE_INCH/_MM). Coordinates are the two in-plane axes, in mm.
#pragma once

#include <numbers>

namespace pkm::cnc {

/// The smallest radius an arc may have, and the most by which an R-format radius may fall
/// short of half the chord: 0.00005 in = 0.00127 mm in both unit systems (LinuxCNC 2.9).
inline constexpr double kArcRadiusToleranceMm = 0.00127;

/// The absolute tolerance t of a centre-format arc's two radii, per unit system: the INI keys
/// [RS274NGC] CENTER_ARC_RADIUS_TOLERANCE_MM and _INCH. The defaults are LinuxCNC 2.9's
/// 2·0.01·√2 mm and 2·0.001·√2 in (an end point rounded to 0.01 mm or 0.001 in passes); an INI
/// value must lie in [0.001 mm, default] and [0.00004 in, default].
struct ArcTolerances {
  static constexpr double kDefaultMm = 2.0 * 0.01 * std::numbers::sqrt2;
  static constexpr double kDefaultInch = 2.0 * 0.001 * std::numbers::sqrt2;
  static constexpr double kMinimumMm = 0.001;
  static constexpr double kMinimumInch = 0.00004;
  double centre_mm = kDefaultMm;      ///< t in G21 programs, mm
  double centre_inch = kDefaultInch;  ///< t in G20 programs, inch
  /// t for a program in inches (`inch`) or mm, converted to mm.
  [[nodiscard]] double centreMm(bool inch) const;
  /// Throws pkm::InvalidArgument when a tolerance lies outside its range.
  void validate() const;
};

/// An arc's centre in the plane and its radius (mm).
struct ArcCentre {
  double c1 = 0.0;
  double c2 = 0.0;
  double radius = 0.0;
};

/// Checks a centre-format arc: start (s1,s2), end (e1,e2), centre (c1,c2), all mm. With r1, r2
/// the radii to start and end, e = |r1 − r2| and t = `tolerance_mm` (ArcTolerances::centreMm),
/// the arc is refused when e > 100·t, or when e > t and e / max(r1, r2) > 0.1 % (LinuxCNC 2.9's
/// rule; its G-code reference quotes older figures). Throws GcodeError (a radius below
/// kArcRadiusToleranceMm, radii that differ).
ArcCentre arcFromCentre(
    double s1, double s2, double e1, double e2, double c1, double c2, double tolerance_mm);

/// Radius-format arc from (s1,s2) to (e1,e2) with signed radius `r` (mm): r > 0 for an arc of at
/// most 180 degrees, r < 0 for more; `clockwise` for G2. The centre lies on the perpendicular
/// bisector of the chord, left of it for G3 with r > 0 and right for G2 with r > 0 (mirrored for
/// r < 0). Throws GcodeError when start and end coincide (no full circle in R format) or the
/// radius is shorter than half the chord by more than kArcRadiusToleranceMm.
ArcCentre arcFromRadius(double s1, double s2, double e1, double e2, double r, bool clockwise);

}  // namespace pkm::cnc
