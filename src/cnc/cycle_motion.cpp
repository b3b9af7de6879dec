// Canned cycles in the interpreter (LinuxCNC 2.9 G-code reference, "Canned Cycles"): the words
// a cycle block needs, its sticky values, and its expansion (canned_cycle.hpp) turned into
// motions in the active plane.
#include <fmt/format.h>

#include <array>
#include <cmath>

#include "interpreter_impl.hpp"
#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {

namespace {

/// Rejects a canned cycle under inverse time, with A, B or C words, or at
/// zero feed rate.
void checkCycleModes(const ResolvedBlock& rb, const MachineState& st) {
  if (st.inverse_time) throw GcodeError("canned cycles are not allowed in inverse time (G93)");
  for (char l : {'a', 'b', 'c'})
    if (rb.hasWord(l)) throw GcodeError(fmt::format("cannot move {} in a canned cycle", l));
  if (st.feed <= 0.0) throw GcodeError("cannot do a canned cycle with zero feed rate");
}

/// A canned cycle's L word (repeats); rejects one that is not a positive integer.
int cycleRepeats(double l) {
  if (!(l >= 0.5 && l < 1e9)) throw GcodeError("canned cycle L must be a positive integer");
  const int repeats = static_cast<int>(std::round(l));
  if (std::abs(l - repeats) > 0.0001 || repeats < 1)
    throw GcodeError("canned cycle L must be a positive integer");
  return repeats;
}

}  // namespace

void Interpreter::Impl::cycle(const ResolvedBlock& rb, int code, MoveSink& sink) {
  checkCycleModes(rb, st);
  // The cycle works in the active plane (LinuxCNC's G17 XY/Z, G18 ZX/Y, G19 YZ/X): the
  // expansion's x, y, z are the plane's first and second axes and the hole axis.
  cycle_axes = planeAxes(st.plane);
  cycle_code = code;
  const char w1 = kAxisWords[cycle_axes[0]], w2 = kAxisWords[cycle_axes[1]];
  const char wn = kAxisWords[cycle_axes[2]];
  const bool entering = st.motion != code;
  if (entering && !rb.hasWord(wn))
    throw GcodeError(
        fmt::format("{} missing in the first block of a canned cycle", static_cast<char>(wn - 32)));
  if (entering && !rb.hasWord('r'))
    throw GcodeError("R missing in the first block of a canned cycle");
  const double s = st.scale();
  CycleRequest q;
  q.code = code / 10;
  for (std::size_t i = 0; i < 3; ++i) q.current[i] = st.program(cycle_axes[i]);
  if (!cycle_il_flag) {  // first cycle block since a non-cycle motion mode: its hole-axis level
    cycle_il = q.current[2];
    cycle_il_flag = true;
  }
  q.initial_level = cycle_il;
  q.incremental = st.incremental;
  q.retract_to_r = st.retract_to_r;
  q.has_x = rb.hasWord(w1);
  q.has_y = rb.hasWord(w2);
  q.x = rb.word(w1) * s;
  q.y = rb.word(w2) * s;
  if (rb.hasWord('r')) cycle_r = rb.word('r') * s;
  if (rb.hasWord(wn)) cycle_cc = rb.word(wn) * s;
  q.r = cycle_r;
  q.z = cycle_cc;
  cycleStickyWords(rb, code, entering, q);
  q.overrides_enabled = st.overrides_enabled;
  q.spindle = st.spindle_direction > 0   ? SpindleDirection::kClockwise
              : st.spindle_direction < 0 ? SpindleDirection::kCounterClockwise
                                         : SpindleDirection::kStopped;
  if (rb.hasWord('l')) q.repeats = cycleRepeats(rb.word('l'));
  if (rb.hasWord(kPolarRadius) || rb.hasWord(kPolarAngle)) {  // G91 polar (applyPolar left them)
    if (st.plane != Plane::kXY)
      throw GcodeError("polar coordinates (@, ^) in a canned cycle need the XY plane (G17)");
    q.polar = true;
    q.polar_radius = rb.word(kPolarRadius) * s;
    q.polar_angle = rb.word(kPolarAngle);
  }
  q.max_steps = options.max_loop_iterations;
  cycle_steps.clear();
  expandCycle(q, cycle_steps);
  emitCycleSteps(rb.line, sink);
}

void Interpreter::Impl::cycleStickyWords(const ResolvedBlock& rb,
                                         int code,
                                         bool entering,
                                         CycleRequest& q) {
  const double s = st.scale();
  if (code == 830 || code == 730) {
    if (entering && !rb.hasWord('q'))
      throw GcodeError(fmt::format("Q word missing with G{}", code / 10));
    if (rb.hasWord('q')) cycle_q = rb.word('q') * s;
    q.q = cycle_q;
  }
  if (code == 820 || code == 860 || code == 880 || code == 890 || code == 840 || code == 740) {
    // G84/G74 default to the sticky P (0 at start-up); the others need P in their first block.
    if (entering && !rb.hasWord('p') && code != 840 && code != 740)
      throw GcodeError(fmt::format("dwell time P word missing with G{}", code / 10));
    if (rb.hasWord('p')) {
      if (rb.word('p') < 0.0) throw GcodeError("negative dwell time P in a canned cycle");
      cycle_p = rb.word('p');
    }
    q.p = cycle_p;
  }
  if (code == 870) {
    // The offsets along the plane's axes and the top of the bore along the hole axis: the
    // I, J, K word of each axis (G18: K, I, J; G19: J, K, I).
    const char o1 = kOffsetWords[cycle_axes[0]], o2 = kOffsetWords[cycle_axes[1]];
    const char on = kOffsetWords[cycle_axes[2]];
    for (char l : {'i', 'j', 'k'})
      if (entering && !rb.hasWord(l))
        throw GcodeError(fmt::format("{} word missing with G87", static_cast<char>(l - 32)));
    if (rb.hasWord(o1)) cycle_i = rb.word(o1) * s;
    if (rb.hasWord(o2)) cycle_j = rb.word(o2) * s;
    if (rb.hasWord(on)) cycle_k = rb.word(on) * s;
    q.i = cycle_i;
    q.j = cycle_j;
    q.k = cycle_k;
  }
}

Axes Interpreter::Impl::cyclePoint(const std::array<double, 3>& local,
                                   const std::array<std::size_t, 3>& axes) const {
  if (st.rotation == 0.0) {  // exact per axis
    Axes to = st.machine;
    for (std::size_t i = 0; i < 3; ++i)
      to[axes[i]] = local[i] + st.g5x[axes[i]] + st.g92[axes[i]] + st.tool_offset[axes[i]];
    return to;
  }
  Axes p = st.programPosition();
  for (std::size_t i = 0; i < 3; ++i) p[axes[i]] = local[i];
  return st.toMachine(p);
}

void Interpreter::Impl::emitCycleSteps(std::size_t line, MoveSink& sink) {
  for (const CycleStep& step : cycle_steps) {
    switch (step.kind) {
      case CycleStep::Kind::kDwell:
        sink.onDwell(line, step.seconds);
        break;
      case CycleStep::Kind::kAction:
        sink.onCycleAction(line, step.action);
        break;
      case CycleStep::Kind::kManual:
        // G88: the operator retracts by hand; the program goes on from the clear level.
        st.machine = cyclePoint(step.to, cycle_axes);
        break;
      case CycleStep::Kind::kRapid:
      case CycleStep::Kind::kFeed: {
        std::array<std::size_t, 3> axes = cycle_axes;
        if (step.kind == CycleStep::Kind::kFeed && (cycle_code == 740 || cycle_code == 840)) {
          // LinuxCNC 2.9 hands a tap's feed to the canon in the wrong axis order outside G17,
          // and the machine follows it (rs274; LinuxCNC's own tests/interp/g84 expect it): in
          // G18 the depth goes to X, the Z position to Y, the X position to Z; in G19 the depth
          // to Y, the Y position to Z, the Z position to X. pkm makes the same moves.
          if (st.plane == Plane::kXZ) axes = {1, 2, 0};
          if (st.plane == Plane::kYZ) axes = {2, 0, 1};
        }
        emitLine(line, step.kind == CycleStep::Kind::kRapid, cyclePoint(step.to, axes), 0.0, sink);
        if (axes != cycle_axes)  // the interpreter goes on from where it meant to feed to
          st.machine = cyclePoint(step.to, cycle_axes);
        break;
      }
    }
  }
}

}  // namespace pkm::cnc
