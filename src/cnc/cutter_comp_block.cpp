// The interpreter's side of cutter radius compensation: G40/G41/G42/G41.1/G42.1 words, the tool
// radius they take, and what LinuxCNC 2.9 refuses while compensation is on (the geometry is in
// cutter_comp.cpp).
#include <fmt/format.h>

#include <cmath>

#include "interpreter_impl.hpp"
#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {

double Interpreter::Impl::compRadius(const ResolvedBlock& rb, int code) const {
  const int g = code / 10;
  if (code == 411 || code == 421) {  // dynamic: D is the diameter
    if (!rb.hasWord('d')) throw GcodeError(fmt::format("G{}.1 with no D word", g));
    if (rb.hasWord('l')) {
      if (st.plane != Plane::kXZ)
        throw GcodeError(fmt::format("G{}.1 with L word, but plane is not G18", g));
      const int orientation = toInt(rb.word('l'), 'L');
      if (orientation != 0 && orientation != 9)
        throw GcodeError(fmt::format(
            "G{}.1 L{}: lathe tool orientations (lathe cutter compensation) are not supported",
            g,
            orientation));
    }
    return 0.5 * rb.word('d') * st.scale();
  }
  int tool = st.tool_in_spindle;
  if (rb.hasWord('d')) {
    const double d = rb.word('d');
    const double n = std::round(d);
    if (std::abs(d - n) > 0.0001 || std::abs(n) > 1e9)
      throw GcodeError(fmt::format("G{} requires D word to be a whole number", g));
    if (n < 0) throw GcodeError("negative D word tool radius index used");
    if (n != 0) tool = static_cast<int>(n);
    if (n != 0 && options.tools.find(tool) == nullptr)
      throw GcodeError(fmt::format("requested tool {} not found in the tool table", tool));
  }
  const ToolEntry* entry = options.tools.find(tool);
  return entry == nullptr ? 0.0 : 0.5 * entry->diameter;
}

void Interpreter::Impl::cutterCompensation(const ResolvedBlock& rb, int code, MoveSink& sink) {
  if (code == 400) {
    CountingSink counted(sink, summary, st.inch);
    comp.stop(counted, st.inch);
    return;
  }
  if (comp.on()) throw GcodeError("cannot turn cutter radius compensation on when it is on");
  if (st.plane == Plane::kYZ)
    throw GcodeError("cutter radius compensation is allowed only in the XY and XZ planes");
  const CompSide side = code == 410 || code == 411 ? CompSide::kLeft : CompSide::kRight;
  comp.start(side, compRadius(rb, code), st.plane);
}

void Interpreter::Impl::flushCompensation(MoveSink& sink) {
  CountingSink counted(sink, summary, st.inch);
  comp.flush(counted, st.inch);
}

void Interpreter::Impl::checkCompRestrictions(const ResolvedBlock& rb, const BlockCodes& c) const {
  if (!comp.on()) return;
  const auto refuse = [](const char* what) {
    throw GcodeError(fmt::format("cannot {} with cutter radius compensation on", what));
  };
  if (c.plane == 190) refuse("select the YZ plane (G19)");
  if ((c.plane == 170 && st.plane != Plane::kXY) || (c.plane == 180 && st.plane != Plane::kXZ))
    refuse("change planes");
  if (c.wcs >= 0) refuse("change coordinate systems");
  if (c.path >= 0) refuse("change the path control mode (G61/G64)");
  if (c.retract >= 0) refuse("change the retract mode (G98/G99)");
  if (c.non_modal >= 920 || c.non_modal == 520) refuse("change axis offsets (G52/G92)");
  if (c.non_modal == 280 || c.non_modal == 300) refuse("use G28 or G30");
  if (c.non_modal == 281 || c.non_modal == 301) refuse("set a reference point (G28.1/G30.1)");
  if (c.non_modal == 100 && rb.hasWord('l') && rb.hasWord('p')) {
    const int l = toInt(rb.word('l'), 'L');
    const int p = toInt(rb.word('p'), 'P');
    if ((l == 2 || l == 20) && (p == 0 || p == st.coordinate_system))
      refuse("change the active coordinate system");
  }
  if (c.m_io >= 62 && c.m_io <= 65) refuse("set an output (M62-M65)");
  if (c.m_io == 66) refuse("wait for an input (M66)");
  if (c.m_io == 67 || c.m_io == 68) refuse("set an analog output (M67/M68)");
  if (c.m_override >= 0 || c.m_switch >= 0) refuse("switch overrides (M48-M53)");
  const int motion = c.motion >= 0 ? c.motion : st.motion;
  const bool moves = rb.hasAxis();
  if (moves && motion >= 382 && motion <= 385) refuse("probe");
  if (moves && motion >= 730 && motion != 800) refuse("use canned cycles");
}

CountingSink::CountingSink(MoveSink& inner, RunSummary& summary, bool inch)
    : inner_(inner), summary_(summary), inch_(inch) {}

void CountingSink::onMove(const Move& move) {
  inner_.onMove(move);
  ++summary_.moves;
  if (inch_) ++summary_.inch_moves;
}

void CountingSink::onDwell(std::size_t line, double seconds) { inner_.onDwell(line, seconds); }

void CountingSink::onMessage(std::size_t line, CommentKind kind, const std::string& text) {
  inner_.onMessage(line, kind, text);
}

}  // namespace pkm::cnc
