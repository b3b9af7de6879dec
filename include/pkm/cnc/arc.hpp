/// @file
/// @brief Arc centres of G2/G3 in the active plane as LinuxCNC 2.9 computes them (G-code
/// reference "G2, G3 Arc Move": centre format with I J K offsets, radius format with R, and the
/// start/end radius check). Coordinates are the two in-plane axes, in mm.
#pragma once

namespace pkm::cnc {

/// An arc's centre in the plane and its radius (mm).
struct ArcCentre {
  double c1 = 0.0;
  double c2 = 0.0;
  double radius = 0.0;
};

/// Checks a centre-format arc: start (s1,s2), end (e1,e2), centre (c1,c2), all mm. The radius to
/// the end may differ from the radius to the start by at most 0.5 mm (0.05 in in G20) and, when
/// it differs by more than 0.005 mm (0.0005 in), by at most 0.1 % (LinuxCNC's rule). `inch` says
/// which of the two tolerance pairs applies. Throws GcodeError (zero radius, radii differ).
ArcCentre arcFromCentre(
    double s1, double s2, double e1, double e2, double c1, double c2, bool inch);

/// Radius-format arc from (s1,s2) to (e1,e2) with signed radius `r` (mm): r > 0 for an arc of at
/// most 180 degrees, r < 0 for more; `clockwise` for G2. The centre lies on the perpendicular
/// bisector of the chord, left of it for G3 with r > 0 and right for G2 with r > 0 (mirrored for
/// r < 0). Throws GcodeError when start and end coincide (no full circle in R format) or the
/// radius is shorter than half the chord by more than the unit tolerance (0.005 mm, 0.0005 in).
ArcCentre arcFromRadius(
    double s1, double s2, double e1, double e2, double r, bool clockwise, bool inch);

}  // namespace pkm::cnc
