// Cutter radius compensation, LinuxCNC 2.9's geometry (include/pkm/cnc/cutter_comp.hpp). Angles
// are in radians in the plane's (first, second) axes; s = +1 for the left side, −1 for the right.
// A corner is classified by beta, the angle the path turns away from the tool's side at the
// corner, in [−π/2, 3π/2): about 0 the path goes straight on, positive the corner is convex
// (the tool passes outside it), negative (or beyond π) concave.
#include "pkm/cnc/cutter_comp.hpp"

#include <cmath>

#include "cutter_comp_geometry.hpp"
#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {

using namespace comp_geometry;  // NOLINT(google-build-using-namespace): private constants

void CutterComp::start(CompSide side, double radius_mm, Plane plane) {
  if (on()) throw GcodeError("cannot turn cutter radius compensation on when it is on");
  if (plane == Plane::kYZ)
    throw GcodeError("cutter radius compensation is allowed only in the XY and XZ planes");
  if (side == CompSide::kOff) return;
  if (radius_mm < 0.0) {
    radius_mm = -radius_mm;
    side = side == CompSide::kLeft ? CompSide::kRight : CompSide::kLeft;
  }
  side_ = side;
  radius_ = radius_mm;
  axes_ = planeAxes(plane);
  first_ = true;
}

void CutterComp::stop(MoveSink& sink, bool inch) {
  if (compensating() && !first_) {
    endHeldAt(tool_, sink, inch);
    start_known_ = false;
    arc_forbidden_ = true;
  }
  side_ = CompSide::kOff;
  first_ = true;
}

void CutterComp::flush(MoveSink& sink, bool inch) {
  endHeldAt(tool_, sink, inch);
  start_known_ = false;
}

Move CutterComp::lineTo(std::size_t line, bool rapid, const Axes& to, P2 at, double feed) const {
  Move m;
  m.line = line;
  m.kind = rapid ? MoveKind::kRapid : MoveKind::kLinear;
  m.end = to;
  m.end[axes_[0]] = at.u;
  m.end[axes_[1]] = at.v;
  m.plane = axes_[2] == 2 ? Plane::kXY : Plane::kXZ;
  m.feed = rapid ? kNaN : feed;
  return m;
}

void CutterComp::hold(const Move& m, P2 dir, double sweep) {
  Held h;
  h.move = m;
  h.dir = dir;
  h.sweep = sweep;
  held_.push_back(std::move(h));
  tool_at_ = m.end;
  displaced_ = true;
}

void CutterComp::release(MoveSink& sink) {
  start_known_ = false;
  for (const Held& h : held_) {
    switch (h.kind) {
      case Held::Kind::kMove:
        sink.onMove(h.move);
        break;
      case Held::Kind::kDwell:
        sink.onDwell(h.move.line, h.seconds);
        break;
      case Held::Kind::kMessage:
        sink.onMessage(h.move.line, h.comment, h.text);
        break;
    }
  }
  held_.clear();
}

const Move* CutterComp::heldPlaneMove() const {
  for (const Held& h : held_)
    if (h.kind == Held::Kind::kMove) return &h.move;
  return nullptr;
}

void CutterComp::endHeldAt(P2 p, MoveSink& sink, bool inch) {
  if (held_.empty()) return;
  // LinuxCNC's limits, in program units: radii of a moved arc end, and its sweep growth (rad).
  const double unit = inch ? kMmPerInch : 1.0;
  const double sweep_slack = inch ? 0.001 : 0.0254;
  for (Held& h : held_) {
    if (h.kind != Held::Kind::kMove) continue;
    Move& m = h.move;
    const auto [a1, a2, an] = axes_;
    if (m.kind == MoveKind::kArc) {
      const double r1 = std::hypot(m.end[a1] - m.centre[a1], m.end[a2] - m.centre[a2]);
      const double r2 = std::hypot(p.u - m.centre[a1], p.v - m.centre[a2]);
      if (std::abs(r1 - r2) > 0.01 * unit)
        throw GcodeError(
            "cutter compensation made an arc with mismatched radii (a corner "
            "of arcs it cannot resolve)");
      const double sweep =
          sweepOf(start_.u, start_.v, m.centre[a1], m.centre[a2], m.turns, p.u, p.v);
      if (h.sweep != 0.0 && start_known_ && std::abs(sweep) > std::abs(h.sweep) + sweep_slack)
        throw GcodeError(
            "arc move in a concave corner cannot be reached by the tool without gouging");
    } else {
      const double dot = h.dir.u * (p.u - start_.u) + h.dir.v * (p.v - start_.v);
      if (start_known_ && dot < 0.0)
        throw GcodeError(m.kind == MoveKind::kRapid
                             ? "straight traverse in a concave corner cannot be reached by the "
                               "tool without gouging"
                             : "straight feed in a concave corner cannot be reached by the tool "
                               "without gouging");
    }
    (void)an;
    m.end[a1] = p.u;
    m.end[a2] = p.v;
  }
  release(sink);
  start_ = p;
  start_known_ = true;
}

void CutterComp::cornerMove(std::size_t line,
                            bool rapid,
                            P2 corner,
                            P2 to,
                            const Axes& end_axes,
                            double feed,
                            MoveSink& sink) {
  Axes end = end_axes;
  end[axes_[2]] = tool_at_[axes_[2]];  // the normal axis moves on the programmed move
  Move m = lineTo(line, rapid, end, to, feed);
  if (!rapid) {
    m.kind = MoveKind::kArc;
    m.centre = {kNaN, kNaN, kNaN};
    m.centre[axes_[0]] = corner.u;
    m.centre[axes_[1]] = corner.v;
    m.turns = side_ == CompSide::kLeft ? -1 : 1;  // around the outside of the corner
  }
  sink.onMove(m);
  tool_at_ = m.end;
  start_ = to;
  start_known_ = true;
}

CutterComp::P2 CutterComp::concaveLineEnd(double beta, double theta) const {
  const double s = side_ == CompSide::kLeft ? 1.0 : -1.0;
  const double half = 0.5 * (beta + kPi);  // half the inside angle of the corner
  if (half == 0.0)
    throw GcodeError("a zero-degree inside corner is invalid for cutter compensation");
  const double back = radius_ / std::tan(half);  // back along the previous move
  const double dir = theta + s * kHalfPi;
  return {tool_.u + back * std::cos(dir), tool_.v + back * std::sin(dir)};
}

CutterComp::P2 CutterComp::arcToLineEnd(const Move& prev, P2 o, double alpha) const {
  // Where the held (compensated) arc meets the offset of the new line.
  const auto [a1, a2, an] = axes_;
  (void)an;
  const double pu = prev.centre[a1], pv = prev.centre[a2];
  const double rad = std::hypot(prev.end[a1] - pu, prev.end[a2] - pv);
  const bool inside = (side_ == CompSide::kLeft) == (prev.turns > 0);
  const double normal = prev.turns > 0 ? alpha + kHalfPi : alpha - kHalfPi;
  const double programmed_rad = inside ? rad + radius_ : rad - radius_;
  const double d = programmed_rad * std::cos(normal - angleOf(pu - o.u, pv - o.v));
  const double l = (inside ? d - radius_ : d + radius_) / rad;
  if (l > 1.0 || l < -1.0)
    throw GcodeError(
        "arc to straight motion makes a corner the compensated tool cannot fit in without "
        "gouging");
  const double turn_sign = prev.turns > 0 ? 1.0 : -1.0;
  const double a = (inside ? -turn_sign : turn_sign) * std::acos(l) + normal + kPi;
  return {pu + rad * std::cos(a), pv + rad * std::sin(a)};
}

void CutterComp::straight(std::size_t line,
                          bool rapid,
                          const Axes& from,
                          const Axes& to,
                          double feed,
                          MoveSink& sink,
                          bool inch) {
  arc_forbidden_ = false;
  const double s = side_ == CompSide::kLeft ? 1.0 : -1.0;
  const P2 o = inPlane(from), p = inPlane(to);
  if (first_) {
    tool_ = o;
    tool_at_ = from;
    if (std::hypot(p.u - o.u, p.v - o.v) < radius_ - kRadiusSlack)
      throw GcodeError("the cutter compensation entry move is not longer than the tool radius");
    const double n = angleOf(p.u - o.u, p.v - o.v) + s * kHalfPi;
    const P2 end{p.u + radius_ * std::cos(n), p.v + radius_ * std::sin(n)};
    start_ = o;
    start_known_ = true;
    hold(lineTo(line, rapid, to, end, feed), P2{}, 0.0);
    first_ = false;
    tool_ = end;
    return;
  }
  if (std::hypot(p.u - o.u, p.v - o.v) <= kNoMotion) {  // no motion in the plane
    hold(lineTo(line, rapid, to, tool_, feed), P2{}, 0.0);
    return;
  }
  const double theta = angleOf(tool_.u - o.u, tool_.v - o.v);  // the tool's side of the corner
  const double alpha = angleOf(p.u - o.u, p.v - o.v);          // the new direction
  double turn = s * (theta - alpha);
  if (turn < 0.0) turn += kTwoPi;
  const double beta = turn - kHalfPi;
  const double n = alpha + s * kHalfPi;
  const P2 end{p.u + radius_ * std::cos(n), p.v + radius_ * std::sin(n)};
  const P2 mid{o.u + radius_ * std::cos(n), o.v + radius_ * std::sin(n)};
  const Move* prev = heldPlaneMove();
  const bool prev_arc = prev != nullptr && prev->kind == MoveKind::kArc;
  // Tool outside a held arc and the line turning back over it (an "h"): stay on that side.
  const bool reversal_over_arc =
      beta > kPi - kCornerTolerance && prev_arc && (side_ == CompSide::kLeft) != (prev->turns > 0);
  const bool concave =
      beta < -kCornerTolerance || beta > kPi + kCornerTolerance || reversal_over_arc;
  if (!concave && beta > kCornerTolerance) {
    endHeldAt(tool_, sink, inch);
    cornerMove(line, rapid, o, mid, to, feed, sink);
  } else if (concave) {
    endHeldAt(prev_arc ? arcToLineEnd(*prev, o, alpha) : concaveLineEnd(beta, theta), sink, inch);
  } else {
    release(sink);
    start_ = tool_;
    start_known_ = true;
  }
  hold(lineTo(line, rapid, to, end, feed), P2{p.u - o.u, p.v - o.v}, 0.0);
  tool_ = end;
}

void CutterComp::dwell(std::size_t line, double seconds, MoveSink& sink) {
  if (held_.empty()) {
    sink.onDwell(line, seconds);
    return;
  }
  Held h;
  h.kind = Held::Kind::kDwell;
  h.move.line = line;
  h.seconds = seconds;
  held_.push_back(std::move(h));
}

void CutterComp::message(std::size_t line,
                         CommentKind kind,
                         const std::string& text,
                         MoveSink& sink) {
  if (held_.empty()) {
    sink.onMessage(line, kind, text);
    return;
  }
  Held h;
  h.kind = Held::Kind::kMessage;
  h.move.line = line;
  h.comment = kind;
  h.text = text;
  held_.push_back(std::move(h));
}

}  // namespace pkm::cnc
