#include "pkm/metrology/min_zone_circle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <utility>
#include <vector>

#include "pkm/core/error.hpp"

namespace pkm::metrology {
namespace {

double cross(const Point2& a, const Point2& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Orientation sign of the triangle (a, b, c): +1 counter-clockwise, −1 clockwise, 0 collinear.
int orientation(const Point2& a, const Point2& b, const Point2& c) {
  const double v = cross(b - a, c - a);
  return (v > 0.0) - (v < 0.0);
}

/// The initial Remez reference about `c`: in the four 90° sectors centred on the farthest point's
/// direction, the farthest point of sectors 0 and 2 and the nearest of sectors 1 and 3 (a guess
/// at the alternation). Falls back to four equal groups in angular order when a sector is empty.
std::array<std::size_t, 4> initialReference(std::span<const Point2> points, const Point2& c) {
  std::size_t far = 0;
  double best = -1.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double d = (points[k] - c).squaredNorm();
    if (d > best) {
      best = d;
      far = k;
    }
  }
  const Point2 u0 = (points[far] - c).normalized();
  const auto sectorOf = [&](const Point2& p) {
    const Point2 v = p - c;
    const double a = v.dot(u0);
    const double b = cross(u0, v);
    if (a >= std::abs(b)) return 0;
    if (b > std::abs(a)) return 1;
    if (-a >= std::abs(b)) return 2;
    return 3;
  };
  std::array<std::size_t, 4> ref{};
  std::array<double, 4> value{
      -1.0, std::numeric_limits<double>::infinity(), -1.0, std::numeric_limits<double>::infinity()};
  std::array<bool, 4> found{};
  for (std::size_t k = 0; k < points.size(); ++k) {
    const int s = sectorOf(points[k]);
    const double d = (points[k] - c).squaredNorm();
    const bool better = (s % 2 == 0) ? d > value[static_cast<std::size_t>(s)]
                                     : d < value[static_cast<std::size_t>(s)];
    if (better) {
      value[static_cast<std::size_t>(s)] = d;
      ref[static_cast<std::size_t>(s)] = k;
      found[static_cast<std::size_t>(s)] = true;
    }
  }
  if (found[0] && found[1] && found[2] && found[3]) return ref;
  // Partial arcs: four consecutive groups of equal count in angular order.
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::vector<double> angle(points.size());
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Point2 v = points[k] - c;
    angle[k] = std::atan2(cross(u0, v), v.dot(u0));
  }
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return angle[a] < angle[b];
  });
  const std::size_t n = points.size();
  for (std::size_t g = 0; g < 4; ++g) {
    const std::size_t lo = g * n / 4;
    const std::size_t hi = (g + 1) * n / 4;
    std::size_t pick = order[lo];
    for (std::size_t i = lo; i < hi; ++i) {
      const double d = (points[order[i]] - c).squaredNorm();
      const double dp = (points[pick] - c).squaredNorm();
      if (g % 2 == 0 ? d > dp : d < dp) pick = order[i];
    }
    ref[g] = pick;
  }
  return ref;
}

/// The optimality condition of the zone about c: the chord of the outer contacts' unit
/// directions from c crosses the chord of the inner contacts' (their directions alternate in
/// angle). For points at nearly one radius this is the crossing of the contacts' own chords; on a
/// partial arc with a wide zone only the directions tell.
bool alternate(const Point2& c,
               const std::array<Point2, 2>& outer,
               const std::array<Point2, 2>& inner) {
  const auto unit = [&](const Point2& p) { return Point2((p - c).normalized()); };
  const Point2 o0 = unit(outer[0]), o1 = unit(outer[1]), i0 = unit(inner[0]), i1 = unit(inner[1]);
  return orientation(o0, o1, i0) * orientation(o0, o1, i1) < 0 &&
         orientation(i0, i1, o0) * orientation(i0, i1, o1) < 0;
}

/// The two farthest and the two nearest points from c as a reference (outer, inner, outer,
/// inner), when their chords cross (alternation); nullopt otherwise. Near a minimum found by the
/// global search these are its contacts.
std::optional<std::array<std::size_t, 4>> activeReference(std::span<const Point2> points,
                                                          const Point2& c) {
  std::array<std::size_t, 2> far{0, 0}, near{0, 0};
  std::array<double, 2> far_d{-1.0, -1.0};
  std::array<double, 2> near_d{std::numeric_limits<double>::infinity(),
                               std::numeric_limits<double>::infinity()};
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double d = (points[k] - c).squaredNorm();
    if (d > far_d[0]) {
      far = {k, far[0]};
      far_d = {d, far_d[0]};
    } else if (d > far_d[1]) {
      far[1] = k;
      far_d[1] = d;
    }
    if (d < near_d[0]) {
      near = {k, near[0]};
      near_d = {d, near_d[0]};
    } else if (d < near_d[1]) {
      near[1] = k;
      near_d[1] = d;
    }
  }
  if (!alternate(c, {points[far[0]], points[far[1]]}, {points[near[0]], points[near[1]]}))
    return std::nullopt;
  return std::array<std::size_t, 4>{far[0], near[0], far[1], near[1]};
}

/// Sorts the reference counter-clockwise about c, starting from ref[0].
void sortCyclic(std::span<const Point2> points, const Point2& c, std::array<std::size_t, 4>& ref) {
  const Point2 u0 = points[ref[0]] - c;
  const auto rel = [&](std::size_t k) {
    const Point2 v = points[k] - c;
    double a = std::atan2(cross(u0, v), u0.dot(v));
    if (a < 0.0) a += 2.0 * std::numbers::pi;
    return a;
  };
  std::sort(
      ref.begin() + 1, ref.end(), [&](std::size_t a, std::size_t b) { return rel(a) < rel(b); });
}

/// The smallest and largest distance of the points from c.
std::pair<double, double> radialRange(std::span<const Point2> points, const Point2& c) {
  double lo2 = std::numeric_limits<double>::infinity();
  double hi2 = 0.0;
  for (const Point2& p : points) {
    const double r2 = (p - c).squaredNorm();
    lo2 = std::min(lo2, r2);
    hi2 = std::max(hi2, r2);
  }
  return {std::sqrt(lo2), std::sqrt(hi2)};
}

/// The points whose distance from `c` lies in the outer or inner tenth of the radial range about
/// c, or all points when that leaves too few.
std::vector<std::size_t> zoneCandidates(std::span<const Point2> points, const Point2& c) {
  constexpr double kEdgeFraction = 0.1;
  const auto [lo, hi] = radialRange(points, c);
  const double band = kEdgeFraction * (hi - lo);
  const double outer2 = (hi - band) * (hi - band);
  const double inner2 = (lo + band) * (lo + band);
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double r2 = (points[k] - c).squaredNorm();
    if (r2 >= outer2 || r2 <= inner2) out.push_back(k);
  }
  if (out.size() < 8) {
    out.resize(points.size());
    std::iota(out.begin(), out.end(), std::size_t{0});
  }
  return out;
}

}  // namespace

std::optional<Point2> bisectorIntersection(const Point2& a,
                                           const Point2& b,
                                           const Point2& c,
                                           const Point2& d) {
  // x = m1 + t·perp(b − a) on the first bisector; (d − c)·(x − m2) = 0 on the second.
  const Point2 ab = b - a;
  const Point2 cd = d - c;
  const Point2 perp(-ab.y(), ab.x());
  const double den = cd.dot(perp);
  if (!(std::abs(den) > 1e-14 * ab.norm() * cd.norm())) return std::nullopt;
  const Point2 m1 = 0.5 * (a + b);
  const Point2 m2 = 0.5 * (c + d);
  const double t = -cd.dot(m1 - m2) / den;
  return m1 + t * perp;
}

ZoneCertificate certifyMinimumZone(std::span<const Point2> points,
                                   const MinZoneCircle& zone,
                                   double tolerance) {
  ZoneCertificate cert;
  std::array<Point2, 2> outer;
  std::array<Point2, 2> inner;
  std::size_t no = 0;
  std::size_t ni = 0;
  for (const ZoneContact& k : zone.contacts) {
    const double r = (k.point - zone.center).norm();
    if (k.outer) {
      if (no < 2) outer[no] = k.point;
      ++no;
      cert.contact_error = std::max(cert.contact_error, std::abs(r - zone.outer_radius));
    } else {
      if (ni < 2) inner[ni] = k.point;
      ++ni;
      cert.contact_error = std::max(cert.contact_error, std::abs(r - zone.inner_radius));
    }
  }
  cert.alternating = no == 2 && ni == 2 && alternate(zone.center, outer, inner);
  for (const Point2& p : points) {
    const double r = (p - zone.center).norm();
    cert.max_violation =
        std::max({cert.max_violation, r - zone.outer_radius, zone.inner_radius - r});
  }
  cert.optimal =
      cert.alternating && cert.contact_error <= tolerance && cert.max_violation <= tolerance;
  return cert;
}

namespace {

/// The exchange's check of every point once it is optimal on `candidates` (sorted, unique): adds
/// the points outside the zone about `c` (mean radius rho, half-width |h| + tol); after
/// kMaxRounds such rounds (counted in `rounds`) all points. False when none was added (or all
/// were candidates already): the zone is optimal on all points.
bool addOutsidePoints(std::span<const Point2> points,
                      const Point2& c,
                      double rho,
                      double h,
                      double tol,
                      std::vector<std::size_t>& candidates,
                      int& rounds) {
  const std::size_t before = candidates.size();
  if (before == points.size()) return false;
  // |r − rho| > |h| + tol, compared as squares (no square root per point).
  const double out_r = rho + std::abs(h) + tol;
  const double in_r = std::max(rho - std::abs(h) - tol, 0.0);
  const double out2 = out_r * out_r, in2 = in_r * in_r;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double r2 = (points[k] - c).squaredNorm();
    if (r2 > out2 || r2 < in2) candidates.push_back(k);
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  if (candidates.size() == before) return false;
  constexpr int kMaxRounds = 8;  // then all points: the plain exchange
  if (++rounds == kMaxRounds) {
    candidates.resize(points.size());
    std::iota(candidates.begin(), candidates.end(), std::size_t{0});
  }
  return true;
}

/// Single-point exchange (Remez): point `worst`, at signed distance worst_e from the mean circle
/// about `c`, replaces the neighbour of its own sign in the cyclically sorted reference `ref`
/// (re-sorted about `c` after), so the reference keeps alternating; group {0, 2} is outer when
/// the levelled half-width h >= 0.
void exchangePoint(std::span<const Point2> points,
                   const Point2& c,
                   double h,
                   std::size_t worst,
                   double worst_e,
                   std::array<std::size_t, 4>& ref) {
  const int sign_a = h >= 0.0 ? 1 : -1;
  const int sign_new = worst_e > 0.0 ? 1 : -1;
  const Point2 u0 = points[ref[0]] - c;
  const auto rel = [&](const Point2& p) {
    const Point2 v = p - c;
    double a = std::atan2(cross(u0, v), u0.dot(v));
    if (a < 0.0) a += 2.0 * std::numbers::pi;
    return a;
  };
  const double beta = rel(points[worst]);
  std::size_t j = 3;
  for (std::size_t i = 1; i < 4; ++i) {
    if (beta < rel(points[ref[i]])) {
      j = i - 1;
      break;
    }
  }
  const int sign_j = (j % 2 == 0) ? sign_a : -sign_a;
  ref[sign_j == sign_new ? j : (j + 1) % 4] = worst;
  sortCyclic(points, c, ref);
  // Keep group {0, 2} = the first group after the re-sort only if the alternation holds; the
  // exchange rule guarantees it for near-circular data.
}

/// The Remez exchange from `start` (fitMinimumZoneCircle without the global proof); `scale` is
/// the length the tolerances are relative to. `from_contacts`: the first reference is the two
/// farthest and two nearest points about `start` when they alternate (a restart at a centre the
/// global search found), else the sector guess.
MinZoneCircle localZone(std::span<const Point2> points,
                        const Point2& start,
                        double scale,
                        const MinZoneOptions& options,
                        bool from_contacts) {
  Point2 c = start;
  PKM_CHECK(std::isfinite(c.x()) && std::isfinite(c.y()) && scale > 0.0,
            "minimum-zone circle: bad start centre");
  const double tol = options.tolerance * scale;

  const auto active = from_contacts ? activeReference(points, c) : std::nullopt;
  std::array<std::size_t, 4> ref = active ? *active : initialReference(points, c);
  sortCyclic(points, c, ref);
  // The exchanges run on candidates, the points near the outer and inner edges of the zone about
  // the start centre; a pass over all points then confirms the result or adds the points that lie
  // outside it, and the exchanges go on. The answer is that of the exchange over all points, at a
  // few passes over them instead of one per exchange.
  std::vector<std::size_t> candidates = zoneCandidates(points, c);
  MinZoneCircle zone;
  double h = 0.0;
  double rho = 0.0;
  bool done = false;
  int it = 0;
  int rounds = 0;
  while (!done && it <= options.max_exchanges) {
    const std::optional<Point2> next =
        bisectorIntersection(points[ref[0]], points[ref[2]], points[ref[1]], points[ref[3]]);
    PKM_CHECK(next.has_value(), "minimum-zone circle: degenerate points (no zone centre)");
    c = *next;
    const double ra = (points[ref[0]] - c).norm();
    const double rb = (points[ref[1]] - c).norm();
    h = 0.5 * (ra - rb);  // levelled half-width; group {0, 2} is outer when h > 0
    rho = 0.5 * (ra + rb);
    std::size_t worst = ref[0];
    double worst_e = 0.0;
    for (const std::size_t k : candidates) {
      const double e = (points[k] - c).norm() - rho;
      if (std::abs(e) > std::abs(worst_e)) {
        worst_e = e;
        worst = k;
      }
    }
    zone.exchanges = it;
    if (std::abs(worst_e) <= std::abs(h) + tol ||
        std::find(ref.begin(), ref.end(), worst) != ref.end()) {
      // Optimal on the candidates: check every point.
      if (!addOutsidePoints(points, c, rho, h, tol, candidates, rounds)) {
        done = true;
        break;
      }
      continue;  // the same reference, now against the added points
    }
    ++it;
    exchangePoint(points, c, h, worst, worst_e, ref);
  }
  zone.center = c;
  const auto [lo, hi] = radialRange(points, c);
  zone.inner_radius = lo;
  zone.outer_radius = hi;
  zone.roundness = hi - lo;
  for (std::size_t i = 0; i < 4; ++i) {
    const bool outer = ((i % 2 == 0) == (h >= 0.0));
    zone.contacts[i] = ZoneContact{ref[i], outer, points[ref[i]]};
  }
  const double cert_tol = 16.0 * options.tolerance * std::max(scale, c.norm());
  zone.certified = done && certifyMinimumZone(points, zone, cert_tol).optimal;
  return zone;
}

}  // namespace

MinZoneCircle fitMinimumZoneCircle(std::span<const Point2> points, const MinZoneOptions& options) {
  PKM_CHECK(options.max_exchanges >= 1, "minimum-zone circle: max_exchanges must be >= 1");
  PKM_CHECK(options.tolerance > 0.0, "minimum-zone circle: tolerance must be > 0");
  PKM_CHECK(options.global_tolerance > 0.0, "minimum-zone circle: global_tolerance must be > 0");
  requirePoints(points, 4, "minimum-zone circle");
  const Circle lsc = options.start ? Circle{*options.start, 0.0} : fitCircle(points).circle;
  double scale = lsc.radius;
  if (!(scale > 0.0)) scale = (points[0] - lsc.center).norm();
  MinZoneCircle zone = localZone(points, lsc.center, scale, options, false);
  ZoneSearchOptions search_options;
  search_options.tolerance = options.global_tolerance * scale;
  search_options.max_boxes = options.max_boxes;
  const ZoneSearch search = searchMinimumZone(points, zone.center, zone.roundness, search_options);
  if (search.best_width < zone.roundness - search_options.tolerance) {
    // Another basin is narrower: the exchange again from the best centre the search saw.
    MinZoneCircle better = localZone(points, search.best_center, scale, options, true);
    better.exchanges += zone.exchanges;
    zone = better;
  }
  zone.certified = zone.certified && search.proven &&
                   zone.roundness <= search.best_width + search_options.tolerance;
  zone.lower_bound = search.proven ? search.lower_bound : 0.0;
  return zone;
}

}  // namespace pkm::metrology
