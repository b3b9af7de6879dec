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
///
/// The exchange finds a local minimum: on a partial arc the zone width has several (Gander, Golub
/// and Strebel, BIT 34 (1994) 558-578, §6: their six points have a local minimum of width 1.3879
/// at (4.6, 4.4) and the global one, 1.3536, at (105/22, 9/22)). searchMinimumZone then proves the
/// result global by branch and bound over the centre, or finds the better basin, from which the
/// exchange starts again. `certified` means both: the local conditions hold and no centre gives a
/// zone narrower by more than the global tolerance.
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
  /// Width resolution of the global proof, relative to the LSC radius: the result is certified
  /// only when no centre gives a zone narrower than roundness − global_tolerance × radius.
  double global_tolerance = 1e-9;
  /// Work cap of the global proof (box evaluations); beyond it the result is not certified.
  std::size_t max_boxes = 2'000'000;
};

/// The minimum-zone circle.
struct MinZoneCircle {
  Point2 center = Point2::Zero();  ///< MZC centre
  double inner_radius = 0.0;       ///< min_k |p_k − centre|
  double outer_radius = 0.0;       ///< max_k |p_k − centre|
  double roundness = 0.0;          ///< zone width outer − inner (RONt, MZC)
  /// The four contacts in counter-clockwise order about the centre, alternating outer/inner.
  std::array<ZoneContact, 4> contacts{};
  int exchanges = 0;  ///< Remez exchanges done
  /// No centre gives a zone narrower than this (the global proof's bound; 0 when not proven).
  double lower_bound = 0.0;
  /// certifyMinimumZone passed on the result and searchMinimumZone proved it global.
  bool certified = false;
};

/// The exact minimum-zone circle of `points` (see the file comment). Throws pkm::InvalidArgument
/// for fewer than 4 points, non-finite or collinear points, or invalid options.
[[nodiscard]] MinZoneCircle fitMinimumZoneCircle(std::span<const Point2> points,
                                                 const MinZoneOptions& options = {});

/// The outcome of checking the optimality conditions of a zone.
struct ZoneCertificate {
  bool alternating = false;    ///< contacts' directions alternate outer/inner (chords cross)
  double contact_error = 0.0;  ///< max | |contact − centre| − its radius |
  double max_violation = 0.0;  ///< max distance of any point outside [inner, outer] (>= 0)
  /// True when alternating and both errors are <= the tolerance given to certifyMinimumZone.
  bool optimal = false;
};

/// Checks the sufficient conditions of a (local) minimum zone: the two outer contacts lie on the
/// outer circle, the two inner ones on the inner circle, every point lies in the zone, and the
/// outer contacts' directions from the centre alternate in angle with the inner ones' (the chords
/// of their unit directions cross). `tolerance` is absolute (points' unit).
[[nodiscard]] ZoneCertificate certifyMinimumZone(std::span<const Point2> points,
                                                 const MinZoneCircle& zone,
                                                 double tolerance);

/// Options of searchMinimumZone.
struct ZoneSearchOptions {
  double tolerance = 1e-9;            ///< width resolution of the proof, points' unit (> 0)
  std::size_t max_boxes = 2'000'000;  ///< box evaluations before giving up (proven = false)
  int directions = 32;                ///< directions of the point set's width bound (>= 4)
};

/// What searchMinimumZone found.
struct ZoneSearch {
  Point2 best_center = Point2::Zero();  ///< the centre of the narrowest zone seen
  double best_width = 0.0;              ///< its zone width (<= the width given to the search)
  /// Proven: no centre anywhere gives a zone narrower than lower_bound = best_width − tolerance.
  bool proven = false;
  double lower_bound = 0.0;  ///< valid when proven
  std::size_t boxes = 0;     ///< box evaluations done
};

/// Global minimum of the zone width w(c) = max_k |p_k − c| − min_k |p_k − c| by branch and bound
/// over the centre c. Every |p_k − c| is 1-Lipschitz in c, so over a square of half-side r about
/// b, w ≥ w(b) − 2√2·r; squares whose bound exceeds the best width − tolerance are discarded, the
/// others split in four. Far centres need no search: with ρ = max_k |p_k − o| about the points'
/// mean o, and W a lower bound of the point set's width over all directions (from `directions`
/// sampled directions), w(c) ≥ W − ρ²/(2(|c − o| − ρ)) for |c − o| > ρ, so no centre beyond
/// ρ + ρ²/(2(W − width)) does better than `width`. Not proven when W <= width (the points are so
/// nearly collinear that a straight zone competes) or the box budget runs out. Only the points
/// that can still be the nearest or the farthest in a surviving square are carried down, so deep
/// levels cost little. `width` and `center`: an upper bound (a zone already found) and its centre.
/// Throws pkm::InvalidArgument for fewer than 3 points, non-finite input or invalid options.
[[nodiscard]] ZoneSearch searchMinimumZone(std::span<const Point2> points,
                                           const Point2& center,
                                           double width,
                                           const ZoneSearchOptions& options = {});

/// The centre equidistant from a and b and from c and d: the intersection of the two perpendicular
/// bisectors (std::nullopt when they are parallel).
[[nodiscard]] std::optional<Point2> bisectorIntersection(const Point2& a,
                                                         const Point2& b,
                                                         const Point2& c,
                                                         const Point2& d);

}  // namespace pkm::metrology
