// Private geometry of the cutter compensation (cutter_comp.cpp, cutter_comp_arcs.cpp).
#pragma once

#include <cmath>
#include <limits>

namespace pkm::cnc::comp_geometry {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kTwoPi = 2.0 * kPi;
inline constexpr double kHalfPi = 0.5 * kPi;
/// Angle within which a corner counts as straight on (LinuxCNC: 0.05 rad).
inline constexpr double kCornerTolerance = 0.05;
/// An in-plane motion shorter than this (mm) is none: the programmed point did not move.
inline constexpr double kNoMotion = 1e-9;
/// How much shorter than the tool radius (mm) an entry move or an arc radius may be and still
/// count as not shorter: LinuxCNC's own rounding (inch tool tables converted to mm and back)
/// accepts the exact boundary in its sample programs (useful-subroutines.ngc), so pkm does too.
inline constexpr double kRadiusSlack = 1e-9;
/// |cos| below which the entry arc's new centre is undefined (LinuxCNC: 1e-6).
inline constexpr double kEqual = 1e-6;
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

inline double angleOf(double u, double v) { return std::atan2(v, u); }

/// Signed sweep (rad) of an arc about (cu, cv) from (su, sv) to (eu, ev) with `turns` turns
/// (positive counter-clockwise); a closed arc sweeps whole turns.
inline double sweepOf(double su, double sv, double cu, double cv, int turns, double eu, double ev) {
  if (turns == 0) return 0.0;
  double a = angleOf(su - cu, sv - cv);
  double b = angleOf(eu - cu, ev - cv);
  if (turns > 0) {
    if (b <= a) b += kTwoPi;
    return b - a + (turns - 1) * kTwoPi;
  }
  if (a <= b) a += kTwoPi;
  return b - a + (turns + 1) * kTwoPi;
}

}  // namespace pkm::cnc::comp_geometry
