// Motion of one block: G0/G1 (with G53), G2/G3 arcs and helices in the active plane, canned
// cycles. Targets are computed in program coordinates (G90 absolute, G91 incremental), then the
// offsets of MachineState map them to machine coordinates, which is what a Move reports.
#include <fmt/format.h>

#include <cmath>
#include <limits>

#include "interpreter_impl.hpp"
#include "pkm/cnc/arc.hpp"
#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {

namespace {

constexpr std::array<char, 6> kAxes{'x', 'y', 'z', 'a', 'b', 'c'};
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Length of a line (mm, or degrees for a rotary-only move) for inverse-time feed.
double pathLength(const Axes& from, const Axes& to) {
  const double l = std::hypot(to[0] - from[0], to[1] - from[1], to[2] - from[2]);
  if (l > 0.0) return l;
  return std::hypot(to[3] - from[3], to[4] - from[4], to[5] - from[5]);
}

/// I, J, K: the centre-offset words of axes X, Y, Z.
constexpr std::array<char, 3> kArcOffsetWord{'i', 'j', 'k'};

/// Rejects an R-format arc (G2 when `clockwise`) without an axis word of plane `plane` (in-plane
/// axes a1, a2; a centre-format arc without one is a full circle, as in rs274), or an arc with
/// the offset word of its normal axis an.
void checkArcWords(const ResolvedBlock& rb,
                   bool clockwise,
                   Plane plane,
                   std::size_t a1,
                   std::size_t a2,
                   std::size_t an) {
  if (rb.hasWord('r') && !rb.hasWord(kAxes[a1]) && !rb.hasWord(kAxes[a2]))
    throw GcodeError(fmt::format("{} R-format arc needs at least one of {} and {} in the {} plane",
                                 clockwise ? "G2" : "G3",
                                 static_cast<char>(kAxes[a1] - 32),
                                 static_cast<char>(kAxes[a2] - 32),
                                 toString(plane)));
  if (rb.hasWord(kArcOffsetWord[an]))
    throw GcodeError(fmt::format("{} word given for an arc in the {} plane",
                                 static_cast<char>(kArcOffsetWord[an] - 32),
                                 toString(plane)));
}

/// An arc's F word under inverse time (G93), 0 otherwise; rejects a missing or zero F word
/// (G93) or a zero feed rate (G94).
double arcInverseFeed(const ResolvedBlock& rb, const MachineState& st, bool clockwise) {
  double inverse_f = 0.0;
  if (st.inverse_time) {
    if (!rb.hasWord('f')) throw GcodeError("F word missing with an inverse time (G93) arc move");
    inverse_f = rb.word('f');
    if (inverse_f <= 0.0) throw GcodeError("zero F word with an inverse time (G93) move");
  } else if (st.feed <= 0.0) {
    throw GcodeError(fmt::format("cannot do {} with zero feed rate", clockwise ? "G2" : "G3"));
  }
  checkFeedPerRev(st);
  return inverse_f;
}

/// An arc's P word (turns; 1 without it); rejects one that is not a positive integer.
int arcTurns(const ResolvedBlock& rb) {
  int turns = 1;
  if (rb.hasWord('p')) {
    const double p = rb.word('p');
    if (!(p >= 0.5 && p < 1e9))
      throw GcodeError(fmt::format("arc P (turns) must be a positive integer, not {}", p));
    turns = static_cast<int>(std::round(p));
    if (std::abs(p - turns) > 0.0001 || turns < 1)
      throw GcodeError(fmt::format("arc P (turns) must be a positive integer, not {}", p));
  }
  return turns;
}

/// The centre of an arc from st.machine to `to` (machine coordinates, mm; in-plane axes a1, a2)
/// by its R word or its I, J, K words (relative to the start, or absolute under G90.1).
ArcCentre arcCentreOf(const ResolvedBlock& rb,
                      const MachineState& st,
                      bool clockwise,
                      std::size_t a1,
                      std::size_t a2,
                      const Axes& to,
                      double tolerance_mm) {
  const double s1 = st.machine[a1], s2 = st.machine[a2];
  const double e1 = to[a1], e2 = to[a2];
  if (rb.hasWord('r')) {
    if (rb.hasWord(kArcOffsetWord[a1]) || rb.hasWord(kArcOffsetWord[a2]))
      throw GcodeError("arc with both R and I/J/K words");
    return arcFromRadius(s1, s2, e1, e2, rb.word('r') * st.scale(), clockwise);
  }
  if (!rb.hasWord(kArcOffsetWord[a1]) && !rb.hasWord(kArcOffsetWord[a2]))
    throw GcodeError(fmt::format("{} arc needs R or at least one of {} and {}",
                                 clockwise ? "G2" : "G3",
                                 static_cast<char>(kArcOffsetWord[a1] - 32),
                                 static_cast<char>(kArcOffsetWord[a2] - 32)));
  const double o1 = rb.hasWord(kArcOffsetWord[a1]) ? rb.word(kArcOffsetWord[a1]) * st.scale() : 0.0;
  const double o2 = rb.hasWord(kArcOffsetWord[a2]) ? rb.word(kArcOffsetWord[a2]) * st.scale() : 0.0;
  const auto offset = [&st](std::size_t i) { return st.g5x[i] + st.g92[i] + st.tool_offset[i]; };
  const double c1 = st.ijk_absolute ? o1 + offset(a1) : s1 + o1;
  const double c2 = st.ijk_absolute ? o2 + offset(a2) : s2 + o2;
  return arcFromCentre(s1, s2, e1, e2, c1, c2, tolerance_mm);
}

/// Helix length (mm) for inverse-time feed: the in-plane sweep of the arc of centre c from
/// `from` to `to` (`turns` turns) times the radius, combined with the travel of the normal axis;
/// axes = {a1, a2, an} of the plane.
double helixLength(const ArcCentre& c,
                   const Axes& from,
                   const Axes& to,
                   const std::array<std::size_t, 3>& axes,
                   bool clockwise,
                   int turns) {
  const auto [a1, a2, an] = axes;
  const double s1 = from[a1], s2 = from[a2];
  const double e1 = to[a1], e2 = to[a2];
  double sweep = std::atan2(e2 - c.c2, e1 - c.c1) - std::atan2(s2 - c.c2, s1 - c.c1);
  const double two_pi = 2.0 * std::acos(-1.0);
  if (clockwise) {
    if (sweep >= 0.0) sweep -= two_pi;
  } else if (sweep <= 0.0) {
    sweep += two_pi;
  }
  const double planar = c.radius * (std::abs(sweep) + two_pi * (turns - 1));
  return std::hypot(planar, to[an] - from[an]);
}

}  // namespace

void Interpreter::Impl::emitLine(
    std::size_t line, bool rapid, const Axes& to, double inverse_f, MoveSink& sink) {
  Move m;
  m.line = line;
  m.kind = rapid ? MoveKind::kRapid : MoveKind::kLinear;
  m.end = to;
  m.plane = st.plane;
  if (!rapid) {
    if (st.inverse_time) {
      m.feed = pathLength(st.machine, to) * inverse_f;
    } else {
      // LinuxCNC's feed rule: a move of X, Y or Z is fed along its XYZ length in length units a
      // minute; a rotary-only move in degrees a minute, F unscaled by G20 (LinuxCNC 2.9 G-code
      // overview, "Feed Rate").
      const bool linear =
          to[0] != st.machine[0] || to[1] != st.machine[1] || to[2] != st.machine[2];
      const bool rotary =
          to[3] != st.machine[3] || to[4] != st.machine[4] || to[5] != st.machine[5];
      m.feed = !linear && rotary ? st.angular_feed : st.feedPerMinute();
      if (st.feed_per_rev && !linear && rotary) m.feed = st.angular_feed * st.spindle_speed;
    }
  }
  st.machine = to;
  sink.onMove(m);
  ++summary.moves;
  if (st.inch) ++summary.inch_moves;
  tlo_at_last_motion = st.tool_offset;
  comp.forgetTool();
}

Axes Interpreter::Impl::axisWords(const ResolvedBlock& rb) const {
  Axes w;
  for (std::size_t i = 0; i < 6; ++i)
    w[i] = rb.hasWord(kAxes[i]) ? rb.word(kAxes[i]) * st.axisScale(i) : kNaN;
  return w;
}

void Interpreter::Impl::straight(const ResolvedBlock& rb, bool rapid, bool g53, MoveSink& sink) {
  Axes to = st.machine;
  if (g53) {
    for (std::size_t i = 0; i < 6; ++i)
      if (rb.hasWord(kAxes[i])) to[i] = rb.word(kAxes[i]) * st.axisScale(i);
  } else {
    to = st.target(axisWords(rb));
  }
  double inverse_f = 0.0;
  if (!rapid) {
    if (st.inverse_time) {
      if (!rb.hasWord('f')) throw GcodeError("F word missing with an inverse time (G93) G1 move");
      inverse_f = rb.word('f');
      if (inverse_f <= 0.0) throw GcodeError("zero F word with an inverse time (G93) move");
    } else if (st.feed <= 0.0) {
      throw GcodeError("cannot do G1 with zero feed rate");
    }
    checkFeedPerRev(st);
  }
  comp.allowArc();
  if (comp.compensating()) {
    if (g53) throw GcodeError("cannot use G53 with cutter radius compensation on");
    const double feed =
        st.inverse_time ? pathLength(st.machine, to) * inverse_f : st.feedPerMinute();
    CountingSink counted(sink, summary, st.inch);
    comp.straight(rb.line, rapid, st.machine, to, feed, counted, st.inch);
    st.machine = to;
    tlo_at_last_motion = st.tool_offset;
    return;
  }
  emitLine(rb.line, rapid, to, inverse_f, sink);
}

void Interpreter::Impl::arc(const ResolvedBlock& rb, bool clockwise, MoveSink& sink) {
  if (comp.arcForbidden())
    throw GcodeError(
        "the move just after exiting cutter compensation mode must be straight, not an arc");
  const std::array<std::size_t, 3> axes = planeAxes(st.plane);
  const auto [a1, a2, an] = axes;
  checkArcWords(rb, clockwise, st.plane, a1, a2, an);
  const double inverse_f = arcInverseFeed(rb, st, clockwise);
  const int turns = arcTurns(rb);
  const Axes to = st.target(axisWords(rb));
  const double tolerance = options.arc.centreMm(st.inch);
  ArcCentre c;
  if (st.rotation == 0.0) {  // offsets are translations: the arc is the same in machine space
    c = arcCentreOf(rb, st, clockwise, a1, a2, to, tolerance);
  } else {
    // A rotated system (G10 L2 R): the arc in program coordinates, its centre turned with it.
    if (st.plane != Plane::kXY)
      throw GcodeError(
          "an arc in G18 or G19 in a rotated coordinate system (G10 L2 R) is not "
          "supported");
    MachineState program = st;
    program.machine = st.programPosition();
    program.g5x = program.g92 = program.tool_offset = Axes{};
    program.rotation = 0.0;
    const Axes end = st.toProgram(to);
    c = arcCentreOf(rb, program, clockwise, a1, a2, end, tolerance);
    Axes centre = end;
    centre[a1] = c.c1;
    centre[a2] = c.c2;
    const Axes on_machine = st.toMachine(centre);
    c.c1 = on_machine[a1];
    c.c2 = on_machine[a2];
  }
  Move m;
  m.line = rb.line;
  m.kind = MoveKind::kArc;
  m.end = to;
  m.centre[a1] = c.c1;
  m.centre[a2] = c.c2;
  m.centre[an] = kNaN;
  m.turns = clockwise ? -turns : turns;
  m.plane = st.plane;
  if (st.inverse_time) {
    m.feed = helixLength(c, st.machine, to, axes, clockwise, turns) * inverse_f;
  } else {
    m.feed = st.feedPerMinute();
  }
  if (comp.compensating()) {
    CountingSink counted(sink, summary, st.inch);
    comp.arc(m, st.machine, counted, st.inch);
  } else {
    sink.onMove(m);
    ++summary.moves;
    if (st.inch) ++summary.inch_moves;
    comp.forgetTool();
  }
  st.machine = to;
  tlo_at_last_motion = st.tool_offset;
}

void Interpreter::Impl::doHome(const ResolvedBlock& rb, int code, MoveSink& sink) {
  const int base = code / 10 == 28 ? kG28Base : kG30Base;
  if (code % 10 == 1) {  // G28.1 / G30.1
    for (std::size_t i = 0; i < 6; ++i) params.set(base + static_cast<int>(i), st.machine[i]);
    return;
  }
  // The intermediate point is a G0 target (offsets, units, G90/G91); rs274 makes this rapid
  // even when it goes nowhere (no axis words).
  const Axes mid = st.target(axisWords(rb));
  const bool any = rb.hasAxis();
  emitLine(rb.line, true, mid, 0.0, sink);
  Axes home = mid;
  for (std::size_t i = 0; i < 6; ++i)
    if (!any || rb.hasWord(kAxes[i])) home[i] = params.get(base + static_cast<int>(i));
  emitLine(rb.line, true, home, 0.0, sink);
}

void Interpreter::Impl::doMotion(const ResolvedBlock& rb, const BlockCodes& c, MoveSink& sink) {
  const int motion = c.motion >= 0 ? c.motion : st.motion;
  const bool is_cycle = motion >= 730 && motion != 800;
  if (!is_cycle) cycle_il_flag = false;  // a non-cycle motion mode ends the cycle sequence
  const bool axis_user0 = c.non_modal == 100 || c.non_modal == 920 || c.non_modal == 520 ||
                          c.non_modal == 280 || c.non_modal == 300 || c.tlo == 431;
  const bool axis = rb.hasAxis() && !axis_user0;
  switch (motion) {
    case 0:
    case 10:
      // A G0/G1 word without axis words moves to where the machine is, as rs274 does
      // (STRAIGHT_TRAVERSE / STRAIGHT_FEED to the current position); a modal G1 does not.
      if (axis || (c.motion >= 0 && !axis_user0))
        straight(rb, motion == 0, c.non_modal == 530, sink);
      break;
    case 20:
    case 30:
      if (axis || c.motion >= 0) arc(rb, motion == 20, sink);
      break;
    case 382:
    case 383:
    case 384:
    case 385:
      if (axis) probe(rb, motion, sink);
      break;
    case 330:
    case 331:
      if (axis) spindleSynchronised(rb, motion, sink);
      break;
    case 800:
      break;
    default:
      if (axis) cycle(rb, motion, sink);
      break;
  }
  st.motion = motion;
}

}  // namespace pkm::cnc
