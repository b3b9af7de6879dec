// Spindle-synchronised motion and spindle modes, as LinuxCNC 2.9's rs274 emits them: G33 (a feed
// whose advance per spindle revolution is K), G33.1 (rigid tapping: in to the target and back to
// the start, the spindle reversing at the bottom), G95 (feed per revolution) and G96/G97
// (constant surface speed / rev per minute). pkm's moves carry the resulting feed in mm/min,
// K (or F) times the programmed spindle speed S (LinuxCNC 2.9 G-code reference, G33, G33.1,
// G95, G96).
#include <fmt/format.h>

#include <cmath>

#include "interpreter_impl.hpp"
#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {

void checkFeedPerRev(const MachineState& st) {
  if (!st.feed_per_rev) return;
  if (st.css)
    throw GcodeError(
        "feed per revolution (G95) under constant surface speed (G96) is not supported: the "
        "spindle speed would follow a lathe's X radius");
  if (st.spindle_speed == 0.0)
    throw GcodeError("cannot feed with zero spindle speed in feed per rev mode");
}

void Interpreter::Impl::spindleMode(const ResolvedBlock& rb, int code) {
  st.css = code == 960;
  st.css_max = st.css && rb.hasWord('d') ? rb.word('d') : 0.0;
}

void Interpreter::Impl::spindleSynchronised(const ResolvedBlock& rb, int code, MoveSink& sink) {
  const char* name = code == 330 ? "G33" : "G33.1";
  if (!rb.hasWord('k')) throw GcodeError("K word missing with G33/G33.1");
  if (st.spindle_direction == 0) throw GcodeError(fmt::format("spindle not turning in {}", name));
  if (comp.on())
    throw GcodeError(fmt::format("cannot use {} with cutter radius compensation on", name));
  if (st.css)
    throw GcodeError(fmt::format(
        "{} under constant surface speed (G96) is not supported: the spindle speed would "
        "follow a lathe's X radius",
        name));
  // The advance per revolution times the spindle speed: the feed the spindle imposes.
  const double feed = std::abs(rb.word('k')) * st.scale() * st.spindle_speed;
  const Axes start = st.machine;
  Axes to = st.target(axisWords(rb));
  Move m;
  m.line = rb.line;
  m.kind = MoveKind::kLinear;
  m.plane = st.plane;
  m.feed = feed;
  if (code == 330) {
    m.end = to;
    sink.onMove(m);
    ++summary.moves;
    st.machine = to;
  } else {
    // Rigid tapping moves X, Y, Z only and ends where it started (rs274's RIGID_TAP).
    for (std::size_t i = 3; i < 6; ++i) to[i] = start[i];
    m.end = to;
    sink.onMove(m);
    m.end = start;
    sink.onMove(m);
    summary.moves += 2;
  }
  if (st.inch) summary.inch_moves += code == 330 ? 1 : 2;
  tlo_at_last_motion = st.tool_offset;
  comp.forgetTool();
}

}  // namespace pkm::cnc
