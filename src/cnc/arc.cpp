// Arc centres, LinuxCNC 2.9 G-code reference "G2, G3 Arc Move" ("Center format", "Radius
// format") with the radius-difference rule and tolerances LinuxCNC 2.9's rs274 applies (arc.hpp;
// checked at both sides of each limit against rs274 in tests/cnc/corpus/arc_tolerance*.ngc).
#include "pkm/cnc/arc.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "pkm/cnc/gcode_error.hpp"
#include "pkm/cnc/modal_state.hpp"
#include "pkm/core/error.hpp"

namespace pkm::cnc {

namespace {
constexpr double kRelativeTolerance = 0.001;  // 0.1 %
constexpr double kAbsoluteCeiling = 100.0;    // e > 100·t is refused whatever the radius
}  // namespace

double ArcTolerances::centreMm(bool inch) const {
  return inch ? centre_inch * kMmPerInch : centre_mm;
}

void ArcTolerances::validate() const {
  PKM_CHECK(centre_mm >= kMinimumMm && centre_mm <= kDefaultMm,
            "CENTER_ARC_RADIUS_TOLERANCE_MM must lie in [{}, {:.6f}] mm, got {}",
            kMinimumMm,
            kDefaultMm,
            centre_mm);
  PKM_CHECK(centre_inch >= kMinimumInch && centre_inch <= kDefaultInch,
            "CENTER_ARC_RADIUS_TOLERANCE_INCH must lie in [{}, {:.7f}] in, got {}",
            kMinimumInch,
            kDefaultInch,
            centre_inch);
}

ArcCentre arcFromCentre(
    double s1, double s2, double e1, double e2, double c1, double c2, double tolerance_mm) {
  const double r1 = std::hypot(s1 - c1, s2 - c2);
  const double r2 = std::hypot(e1 - c1, e2 - c2);
  if (r1 < kArcRadiusToleranceMm || r2 < kArcRadiusToleranceMm)
    throw GcodeError(fmt::format("zero-radius arc: r1={:.4f} r2={:.4f} mm", r1, r2));
  const double abs_err = std::abs(r1 - r2);
  const double rel_err = abs_err / std::max(r1, r2);
  if (abs_err > kAbsoluteCeiling * tolerance_mm ||
      (abs_err > tolerance_mm && rel_err > kRelativeTolerance))
    throw GcodeError(
        fmt::format("radius to end of arc differs from radius to start: r1={:.4f} r2={:.4f} mm "
                    "abs_err={:.4g} mm rel_err={:.4f}%",
                    r1,
                    r2,
                    abs_err,
                    100.0 * rel_err));
  return {c1, c2, r1};
}

ArcCentre arcFromRadius(double s1, double s2, double e1, double e2, double r, bool clockwise) {
  const double d1 = e1 - s1;
  const double d2 = e2 - s2;
  const double chord = std::hypot(d1, d2);
  // LinuxCNC compares the two points exactly; 1e-9 mm absorbs the unit conversion's rounding.
  if (chord <= 1e-9)
    throw GcodeError(
        "radius-format arc with start and end the same point (use I J K for a full "
        "circle)");
  const double abs_r = std::abs(r);
  double half = chord / 2.0;
  if (half - abs_r > kArcRadiusToleranceMm)
    throw GcodeError(
        fmt::format("arc radius {:.4f} mm too small to reach the end point "
                    "(half chord {:.4f} mm)",
                    abs_r,
                    half));
  if (half > abs_r) half = abs_r;
  // Direction from the chord midpoint to the centre: left normal for G3 with r > 0.
  const bool right = (clockwise && r > 0.0) || (!clockwise && r < 0.0);
  const double angle =
      std::atan2(d2, d1) + (right ? -std::numbers::pi / 2.0 : std::numbers::pi / 2.0);
  const double offset = std::sqrt(std::max(0.0, abs_r * abs_r - half * half));
  ArcCentre a;
  a.c1 = s1 + d1 / 2.0 + offset * std::cos(angle);
  a.c2 = s2 + d2 / 2.0 + offset * std::sin(angle);
  a.radius = abs_r;
  return a;
}

}  // namespace pkm::cnc
