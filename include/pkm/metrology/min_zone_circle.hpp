/// @file
/// @brief Minimum-zone (Chebyshev) circle: the two concentric circles of least radial separation
/// that enclose all points (ISO 12181 "MZC"), solved exactly (no linearisation) and certified by
/// its contact points.
///
/// Characterisation used. The zone width about c is w(c) = max_k f_k(c) − min_k f_k(c) with f_k =
/// |p_k − c|, a maximum of the smooth functions f_i − f_j. A minimum needs 0 in the convex hull of
/// their gradients u_j − u_i (u = unit vector from c to the point), i.e. the hull of the outer
/// contacts' directions must meet the hull of the inner contacts' directions. With unit vectors
/// this is impossible for 1 outer + n inner or n outer + 1 inner points; the generic optimum has 2
/// outer and 2 inner contacts that alternate in angle (outer, inner, outer, inner: the chord of the
/// outer pair crosses the chord of the inner pair) — the Chebyshev alternation known from the
/// linearised minimum-zone problem. Its centre is the intersection of the perpendicular bisectors
/// of the outer pair and of the inner pair, found here by a Remez exchange on the exact distances,
/// started from the least-squares centre.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <span>

#include "pkm/metrology/circle_fit.hpp"

namespace pkm::metrology {

/// A contact point of the minimum zone.
struct ZoneContact {
  std::size_t index = 0;          ///< index into the input points
  bool outer = false;             ///< on the outer (true) or inner (false) circle
  Point2 point = Point2::Zero();  ///< the point
};

/// Options of fitMinimumZoneCircle.
struct MinZoneOptions {
  int max_exchanges = 500;  ///< Remez exchanges before giving up (then certified = false)
  /// Optimality tolerance relative to the LSC radius: the exchange stops when no point lies more
  /// than tolerance × radius outside the levelled zone.
  double tolerance = 1e-13;
  std::optional<Point2> start;  ///< start centre; the least-squares centre when absent
};

/// The minimum-zone circle.
struct MinZoneCircle {
  Point2 center = Point2::Zero();  ///< MZC centre
  double inner_radius = 0.0;       ///< min_k |p_k − centre|
  double outer_radius = 0.0;       ///< max_k |p_k − centre|
  double roundness = 0.0;          ///< zone width outer − inner (RONt, MZC)
  /// The four contacts in counter-clockwise order about the centre, alternating outer/inner.
  std::array<ZoneContact, 4> contacts{};
  int exchanges = 0;       ///< Remez exchanges done
  bool certified = false;  ///< certifyMinimumZone passed on the result
};

/// The exact minimum-zone circle of `points` (see the file comment). Throws pkm::InvalidArgument
/// for fewer than 4 points, non-finite or collinear points, or invalid options.
[[nodiscard]] MinZoneCircle fitMinimumZoneCircle(std::span<const Point2> points,
                                                 const MinZoneOptions& options = {});

/// The outcome of checking the optimality conditions of a zone.
struct ZoneCertificate {
  bool alternating = false;    ///< outer chord and inner chord cross (4-point alternation)
  double contact_error = 0.0;  ///< max | |contact − centre| − its radius |
  double max_violation = 0.0;  ///< max distance of any point outside [inner, outer] (>= 0)
  /// True when alternating and both errors are <= the tolerance given to certifyMinimumZone.
  bool optimal = false;
};

/// Checks the sufficient conditions of a (local) minimum zone: the two outer contacts lie on the
/// outer circle, the two inner ones on the inner circle, every point lies in the zone, and the
/// outer chord crosses the inner chord (alternation). `tolerance` is absolute (points' unit).
[[nodiscard]] ZoneCertificate certifyMinimumZone(std::span<const Point2> points,
                                                 const MinZoneCircle& zone,
                                                 double tolerance);

/// The centre equidistant from a and b and from c and d: the intersection of the two perpendicular
/// bisectors (std::nullopt when they are parallel).
[[nodiscard]] std::optional<Point2> bisectorIntersection(const Point2& a,
                                                         const Point2& b,
                                                         const Point2& c,
                                                         const Point2& d);

}  // namespace pkm::metrology
