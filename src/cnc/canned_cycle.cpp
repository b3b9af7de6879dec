// Canned cycles in the XY plane with the motions of Debian's LinuxCNC 2.9 snapshot, established
// against rs274 block by block (docs/gcode.md, "Canned cycles"):
// - the initial level IL is the Z before the first cycle block of a sequence (a non-cycle motion
//   mode ends the sequence; rs274ngc cycle_il);
// - R plane = R (G90) or IL + R (G91); bottom = Z (G90) or R plane + Z (G91);
// - if IL is below the R plane, first a rapid straight up to R at the current XY;
// - clear level = R plane (G99) or the higher of IL and R (G98);
// - per repeat: a rapid to X, Y at the higher of the current Z and the clear level (it may rise
//   diagonally), a rapid down to R when not there, the cycle body, which ends at the clear level.
// Bodies: G81 feed, rapid out; G82 feed, dwell, rapid out; G85 feed in, feed out to R, rapid to
// clear; G89 feed in, dwell, feed out to the clear level; G83 pecks with rapids to R and back to
// 0.254 mm above the last depth; G73 pecks with a 0.254 mm rapid retract. G84 (G74) feeds in
// with the spindle clockwise (counter-clockwise), reverses it, dwells P and feeds out to the
// clear level, restoring the spindle, with the feed and speed overrides off meanwhile; G86 feeds
// in, dwells, stops the spindle, rapids out and restarts it; G88 feeds in, dwells, stops the
// spindle and the program for a manual retraction (the program goes on from the clear level, with
// no motion); G87 back-bores: rapid to the offset point I, J at R, orient the spindle, rapid down
// to the bottom and over to the hole, start the spindle, feed up to K and back down, orient, rapid
// to the offset point, up to the clear level and back over the hole, restart the spindle.
#include "pkm/cnc/canned_cycle.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {

namespace {
void push(std::vector<CycleStep>& out, CycleStep::Kind k, double x, double y, double z) {
  CycleStep s;
  s.kind = k;
  s.to = {x, y, z};
  out.push_back(s);
}

void act(std::vector<CycleStep>& out, CycleAction action, double x, double y, double z) {
  CycleStep s;
  s.kind = CycleStep::Kind::kAction;
  s.action = action;
  s.to = {x, y, z};
  out.push_back(s);
}

void dwell(std::vector<CycleStep>& out, double seconds, double x, double y, double z) {
  CycleStep d;
  d.kind = CycleStep::Kind::kDwell;
  d.to = {x, y, z};
  d.seconds = seconds;
  out.push_back(d);
}

/// The spindle preconditions of the cycles that use it (rs274ngc's messages).
void checkSpindle(int code, SpindleDirection dir) {
  using D = SpindleDirection;
  if (code == 84 || code == 74) {
    if (dir == D::kStopped) throw GcodeError(fmt::format("spindle not turning in G{}", code));
    if (code == 84 && dir == D::kCounterClockwise)
      throw GcodeError("spindle turning counterclockwise in G84");
    if (code == 74 && dir == D::kClockwise) throw GcodeError("spindle turning clockwise in G74");
  }
  if ((code == 86 || code == 87 || code == 88) && dir == D::kStopped)
    throw GcodeError(fmt::format("spindle not turning in G{}", code));
}

CycleAction turning(SpindleDirection dir) {
  return dir == SpindleDirection::kCounterClockwise ? CycleAction::kSpindleCounterClockwise
                                                    : CycleAction::kSpindleClockwise;
}

/// Where a cycle works: the R plane, the bottom, G87's top of the back bore, the hole position
/// before the first repeat and its increment per repeat.
struct CyclePlan {
  double r = 0.0, bottom = 0.0, middle = 0.0;
  double x = 0.0, y = 0.0, dx = 0.0, dy = 0.0;
};

/// The plan of `q`; throws GcodeError for an R plane below the bottom, a bad L or Q, a spindle
/// the cycle cannot use, or too many motions.
CyclePlan planCycle(const CycleRequest& q) {
  CyclePlan p;
  p.r = q.r;
  p.bottom = q.z;
  p.x = q.current[0];
  p.y = q.current[1];
  if (q.incremental) {
    p.r = q.r + q.initial_level;
    p.bottom = p.r + q.z;
    p.dx = q.has_x ? q.x : 0.0;
    p.dy = q.has_y ? q.y : 0.0;
  } else {
    if (q.has_x) p.x = q.x;
    if (q.has_y) p.y = q.y;
  }
  if (p.r < p.bottom) throw GcodeError("R plane below the bottom Z of the canned cycle");
  if (q.repeats < 1) throw GcodeError("canned cycle L must be a positive integer");
  if ((q.code == 73 || q.code == 83) && q.q <= 0.0)
    throw GcodeError("negative or zero Q value in a pecking cycle");
  checkSpindle(q.code, q.spindle);
  p.middle = q.incremental ? p.bottom + q.k : q.k;  // G87's top of the back bore
  const double pecks = (q.code == 73 || q.code == 83) ? std::ceil((p.r - p.bottom) / q.q) : 1.0;
  const double steps = static_cast<double>(q.repeats) * (3.0 * pecks + 14.0);
  if (steps > static_cast<double>(q.max_steps))
    throw GcodeError(
        fmt::format("canned cycle would make {:.3g} motions (more than {})", steps, q.max_steps));
  return p;
}

/// G83 / G73: pecks of Q from R, then the bottom and a rapid out.
void peck(const CycleRequest& q,
          const CyclePlan& p,
          double x,
          double y,
          double clear,
          std::vector<CycleStep>& out) {
  using K = CycleStep::Kind;
  for (double depth = p.r - q.q; depth > p.bottom; depth -= q.q) {
    push(out, K::kFeed, x, y, depth);
    if (q.code == 83) {
      push(out, K::kRapid, x, y, p.r);
      push(out, K::kRapid, x, y, depth + kPeckClearanceMm);
    } else {
      push(out, K::kRapid, x, y, depth + kPeckClearanceMm);
    }
  }
  push(out, K::kFeed, x, y, p.bottom);
  push(out, K::kRapid, x, y, clear);
}

/// G84 / G74: tapping with the spindle reversed at the bottom, overrides off meanwhile.
void tap(const CycleRequest& q,
         const CyclePlan& p,
         double x,
         double y,
         double clear,
         std::vector<CycleStep>& out) {
  using K = CycleStep::Kind;
  using A = CycleAction;
  const A reverse = q.code == 84 ? A::kSpindleCounterClockwise : A::kSpindleClockwise;
  const A forward = q.code == 84 ? A::kSpindleClockwise : A::kSpindleCounterClockwise;
  act(out, A::kOverridesOff, x, y, p.r);
  push(out, K::kFeed, x, y, p.bottom);
  act(out, A::kSpindleStop, x, y, p.bottom);
  act(out, reverse, x, y, p.bottom);
  dwell(out, q.p, x, y, p.bottom);
  push(out, K::kFeed, x, y, clear);
  act(out, A::kSpindleStop, x, y, clear);
  act(out, forward, x, y, clear);
  if (q.overrides_enabled) act(out, A::kOverridesOn, x, y, clear);
}

/// G87: back boring from the offset point I, J.
void backBore(const CycleRequest& q,
              const CyclePlan& p,
              double x,
              double y,
              double clear,
              std::vector<CycleStep>& out) {
  using K = CycleStep::Kind;
  using A = CycleAction;
  const double ox = x + q.i;
  const double oy = y + q.j;
  push(out, K::kRapid, ox, oy, p.r);
  act(out, A::kSpindleStop, ox, oy, p.r);
  act(out, A::kSpindleOrient, ox, oy, p.r);
  push(out, K::kRapid, ox, oy, p.bottom);
  push(out, K::kRapid, x, y, p.bottom);
  act(out, turning(q.spindle), x, y, p.bottom);
  push(out, K::kFeed, x, y, p.middle);
  push(out, K::kFeed, x, y, p.bottom);
  act(out, A::kSpindleStop, x, y, p.bottom);
  act(out, A::kSpindleOrient, x, y, p.bottom);
  push(out, K::kRapid, ox, oy, p.bottom);
  push(out, K::kRapid, ox, oy, clear);
  push(out, K::kRapid, x, y, clear);
  act(out, turning(q.spindle), x, y, clear);
}

/// The body of one repeat at hole x, y, from R to the clear level.
void cycleBody(const CycleRequest& q,
               const CyclePlan& p,
               double x,
               double y,
               double clear,
               std::vector<CycleStep>& out) {
  using K = CycleStep::Kind;
  const double r = p.r;
  const double bottom = p.bottom;
  switch (q.code) {
    case 81:
      push(out, K::kFeed, x, y, bottom);
      push(out, K::kRapid, x, y, clear);
      break;
    case 82:
    case 89: {
      push(out, K::kFeed, x, y, bottom);
      dwell(out, q.p, x, y, bottom);
      if (q.code == 89)
        push(out, K::kFeed, x, y, clear);  // G89 feeds all the way out (rs274)
      else
        push(out, K::kRapid, x, y, clear);
      break;
    }
    case 85:
      push(out, K::kFeed, x, y, bottom);
      push(out, K::kFeed, x, y, r);
      push(out, K::kRapid, x, y, clear);
      break;
    case 83:
    case 73:
      peck(q, p, x, y, clear, out);
      break;
    case 84:
    case 74:
      tap(q, p, x, y, clear, out);
      break;
    case 86:
      push(out, K::kFeed, x, y, bottom);
      dwell(out, q.p, x, y, bottom);
      act(out, CycleAction::kSpindleStop, x, y, bottom);
      push(out, K::kRapid, x, y, clear);
      act(out, turning(q.spindle), x, y, clear);
      break;
    case 88:
      push(out, K::kFeed, x, y, bottom);
      dwell(out, q.p, x, y, bottom);
      act(out, CycleAction::kSpindleStop, x, y, bottom);
      act(out, CycleAction::kProgramStop, x, y, bottom);
      push(out, K::kManual, x, y, clear);
      act(out, turning(q.spindle), x, y, clear);
      break;
    case 87:
      backBore(q, p, x, y, clear, out);
      break;
    default:
      throw GcodeError("unsupported canned cycle");
  }
}

}  // namespace

std::array<double, 3> expandCycle(const CycleRequest& q, std::vector<CycleStep>& out) {
  using K = CycleStep::Kind;
  const CyclePlan p = planCycle(q);
  double old_z = q.initial_level;
  double x = p.x;
  double y = p.y;
  double z = q.current[2];
  if (old_z < p.r) {
    push(out, K::kRapid, q.current[0], q.current[1], p.r);
    old_z = p.r;
    z = p.r;
  }
  const double clear = q.retract_to_r ? p.r : old_z;
  for (int rep = 0; rep < q.repeats; ++rep) {
    if (q.polar) {
      if (x == 0.0 && y == 0.0)
        throw GcodeError("G91 motion with polar coordinates is indeterminate at the origin");
      const double r = std::hypot(x, y) + q.polar_radius;
      const double t = std::atan2(y, x) + q.polar_angle * std::numbers::pi / 180.0;
      x = r * std::cos(t);
      y = r * std::sin(t);
    } else {
      x += p.dx;
      y += p.dy;
    }
    // The first repeat starting above R goes over at its own level; any other at the clear
    // level (rs274: a later repeat, or a start at R, under G98 rises to the initial level).
    const bool from_above = rep == 0 && z > p.r;
    const double level = from_above ? z : clear;
    push(out, K::kRapid, x, y, level);
    if (level != p.r) push(out, K::kRapid, x, y, p.r);
    cycleBody(q, p, x, y, clear, out);
    z = clear;
  }
  return {x, y, clear};
}

}  // namespace pkm::cnc
