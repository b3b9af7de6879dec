// Cutter radius compensation of arcs: the entry arc, and arcs after a line or an arc (convex
// corners get a corner arc, concave ones move the held move's end to where the offsets meet).
#include <cmath>

#include "cutter_comp_geometry.hpp"
#include "pkm/cnc/cutter_comp.hpp"
#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {

using namespace comp_geometry;  // NOLINT(google-build-using-namespace): private constants

void CutterComp::arc(const Move& programmed, const Axes& from, MoveSink& sink, bool inch) {
  if (first_) {
    arcEntry(programmed, from);
    return;
  }
  arcNext(programmed, from, sink, inch);
}

void CutterComp::arcEntry(const Move& programmed, const Axes& from) {
  const auto [a1, a2, an] = axes_;
  (void)an;
  const P2 c = inPlane(from), e = inPlane(programmed.end);
  const P2 centre{programmed.centre[a1], programmed.centre[a2]};
  tool_ = c;
  tool_at_ = from;
  if (std::hypot(e.u - c.u, e.v - c.v) < radius_ - kRadiusSlack)
    throw GcodeError("the cutter compensation entry arc is not longer than the tool radius");
  const bool inside = (side_ == CompSide::kLeft) == (programmed.turns > 0);
  if (inside && std::hypot(centre.u - c.u, centre.v - c.v) < radius_ - kRadiusSlack)
    throw GcodeError("the tool radius is not less than the arc radius with cutter compensation");
  const double g =
      inside ? angleOf(centre.u - e.u, centre.v - e.v) : angleOf(e.u - centre.u, e.v - centre.v);
  const P2 end{e.u + radius_ * std::cos(g), e.v + radius_ * std::sin(g)};
  // The compensated arc runs from the tool to `end`; its centre lies on the line from `end`
  // towards the programmed centre, equidistant from both ends.
  const double to_centre = angleOf(centre.u - end.u, centre.v - end.v);
  const double half_chord = 0.5 * std::hypot(c.u - end.u, c.v - end.v);
  const double corner = angleOf(c.u - end.u, c.v - end.v) - to_centre;
  if (std::abs(std::cos(corner)) < kEqual)
    throw GcodeError("the tool radius is not less than the arc radius with cutter compensation");
  const double len = half_chord / std::cos(corner);
  const P2 new_centre{end.u + len * std::cos(to_centre), end.v + len * std::sin(to_centre)};
  Move m = programmed;
  m.end[a1] = end.u;
  m.end[a2] = end.v;
  m.centre[a1] = new_centre.u;
  m.centre[a2] = new_centre.v;
  hold(m, P2{}, sweepOf(c.u, c.v, new_centre.u, new_centre.v, m.turns, end.u, end.v));
  first_ = false;
  tool_ = end;
}

void CutterComp::arcNext(const Move& programmed, const Axes& from, MoveSink& sink, bool inch) {
  const auto [a1, a2, an] = axes_;
  (void)an;
  const double s = side_ == CompSide::kLeft ? 1.0 : -1.0;
  const P2 o = inPlane(from), e = inPlane(programmed.end);
  const P2 centre{programmed.centre[a1], programmed.centre[a2]};
  const int turns = programmed.turns;
  const double arc_radius = std::hypot(centre.u - e.u, centre.v - e.v);
  const double theta = angleOf(tool_.u - o.u, tool_.v - o.v) - s * kHalfPi;  // last direction
  double delta = angleOf(centre.u - o.u, centre.v - o.v);
  const double alpha = turns > 0 ? delta - kHalfPi : delta + kHalfPi;  // the arc's start tangent
  double beta = s * (theta - alpha);
  if (beta > 1.5 * kPi) beta -= kTwoPi;
  if (beta < -kHalfPi) beta += kTwoPi;
  const bool inside = (side_ == CompSide::kLeft) == (turns > 0);
  double g = 0.0;
  if (inside) {
    g = angleOf(centre.u - e.u, centre.v - e.v);
    if (arc_radius < radius_ - kRadiusSlack)
      throw GcodeError("the tool radius is not less than the arc radius with cutter compensation");
  } else {
    g = angleOf(e.u - centre.u, e.v - centre.v);
    delta += kPi;
  }
  const P2 end{e.u + radius_ * std::cos(g), e.v + radius_ * std::sin(g)};
  Move m = programmed;
  m.end[a1] = end.u;
  m.end[a2] = end.v;
  const double sweep = sweepOf(o.u, o.v, centre.u, centre.v, turns, e.u, e.v);
  const bool concave = beta < -kCornerTolerance || beta > kPi + kCornerTolerance ||
                       (std::abs(beta - kPi) < kCornerTolerance && !inside);
  if (concave) {
    const Move* prev = heldPlaneMove();
    if (prev != nullptr && prev->kind == MoveKind::kArc) {
      endHeldAt(
          arcToArcEnd(*prev, centre, inside ? arc_radius - radius_ : arc_radius + radius_, turns),
          sink,
          inch);
    } else {
      endHeldAt(lineToArcEnd(centre, arc_radius, beta, theta, inside, turns), sink, inch);
    }
  } else if (beta > kCornerTolerance) {
    release(sink);
    const P2 mid{o.u + radius_ * std::cos(delta), o.v + radius_ * std::sin(delta)};
    cornerMove(programmed.line, false, o, mid, programmed.end, programmed.feed, sink);
  } else {
    release(sink);
    start_ = tool_;
    start_known_ = true;
  }
  hold(m, P2{}, sweep);
  tool_ = end;
}

CutterComp::P2 CutterComp::lineToArcEnd(
    P2 centre, double arc_radius, double beta, double theta, bool inside, int turns) const {
  // Where the held line's offset meets the offset of the arc.
  const double across = arc_radius * std::sin(beta - kHalfPi);
  const double dist = inside ? arc_radius - radius_ : arc_radius + radius_;
  const double l = (inside ? across + radius_ : across - radius_) / dist;
  if (l > 1.0 || l < -1.0)
    throw GcodeError("arc move in a concave corner cannot be reached by the tool without gouging");
  const double turn_sign = turns > 0 ? 1.0 : -1.0;
  const double a =
      inside ? theta + turn_sign * std::asin(l) : theta + kPi - turn_sign * std::asin(l);
  return {centre.u + dist * std::cos(a), centre.v + dist * std::sin(a)};
}

CutterComp::P2 CutterComp::arcToArcEnd(const Move& prev,
                                       P2 centre,
                                       double new_rad,
                                       int turns) const {
  // Where the held (compensated) arc meets the offset of the new arc: a triangle of the two
  // centres and the meeting point.
  const auto [a1, a2, an] = axes_;
  (void)an;
  const double pu = prev.centre[a1], pv = prev.centre[a2];
  const double old_rad = std::hypot(prev.end[a1] - pu, prev.end[a2] - pv);
  const double centres = std::hypot(centre.u - pu, centre.v - pv);
  if (old_rad == 0.0 || centres == 0.0)
    throw GcodeError("arc to arc motion is invalid because the arcs have the same centre");
  const double c =
      (old_rad * old_rad + centres * centres - new_rad * new_rad) / (2.0 * old_rad * centres);
  if (c > 1.0 || c < -1.0)
    throw GcodeError(
        "arc to arc motion makes a corner the compensated tool cannot fit in without gouging");
  const bool prev_inside = (side_ == CompSide::kLeft) == (prev.turns > 0);
  const double pullback = prev_inside == (turns > 0) ? std::acos(c) : -std::acos(c);
  const double a = angleOf(centre.u - pu, centre.v - pv) + pullback;
  return {pu + old_rad * std::cos(a), pv + old_rad * std::sin(a)};
}

}  // namespace pkm::cnc
