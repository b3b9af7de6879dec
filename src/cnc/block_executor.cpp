// One block: evaluate its words, check modal groups and word use, then execute in LinuxCNC's
// order of execution (LinuxCNC 2.9 G-code overview, "G-code Order of Execution"): feed mode, F,
// S, T, M6, spindle, coolant, G4, plane, units, cutter compensation, tool length offset,
// coordinate system, path mode, distance mode, retract mode, G10/G92, motion, M0/M1/M2/M30.
#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "interpreter_impl.hpp"
#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {

namespace {

constexpr double kIntegerTolerance = 0.0001;  // integer-valued words accept reals within this
constexpr double kDegreesPerRadian = 180.0 / std::numbers::pi;

}  // namespace

int toInt(double v, char letter) {
  const double r = std::round(v);
  if (std::abs(v - r) > kIntegerTolerance || std::abs(r) > 1e9)
    throw GcodeError(fmt::format("{} word value {} is not an integer", letter, v));
  return static_cast<int>(r);
}

std::string gName(int code) {
  return code % 10 == 0 ? fmt::format("G{}", code / 10)
                        : fmt::format("G{}.{}", code / 10, code % 10);
}

void Interpreter::Impl::resolve(const Block& block, ResolvedBlock& rb, MoveSink& sink) {
  // A block of a sub file reports the main program's line that called the file.
  rb.line = external_depth > 0 ? external_call_line : block.line;
  if (report_blocks) evaluated.clear();
  for (const Word& w : block.words) {
    const double v = w.value.evaluate(*this);
    if (report_blocks) evaluated.push_back({w.letter, v});
    if (w.letter == 'g' || w.letter == 'm') {
      if (w.letter == 'g') {
        const double t = v * 10.0;
        const double r = std::round(t);
        if (std::abs(t - r) > 10.0 * kIntegerTolerance || r < 0.0 || r > 9999.0)
          throw GcodeError(fmt::format("bad G code number {}", v));
        if (rb.n_g == static_cast<int>(rb.g.size()))
          throw GcodeError("too many G codes on one line");
        rb.g[static_cast<std::size_t>(rb.n_g++)] = static_cast<int>(r);
      } else {
        const int m = toInt(v, 'M');
        if (rb.n_m == static_cast<int>(rb.m.size()))
          throw GcodeError("too many M codes on one line");
        rb.m[static_cast<std::size_t>(rb.n_m++)] = m;
      }
      continue;
    }
    const auto i = static_cast<std::size_t>(w.letter - 'a');
    rb.value[i] = v;
    rb.has |= letterBit(w.letter);
  }
  if (report_blocks) sink.onBlock(block, block_index, evaluated);
  // Parameter settings take effect after every value on the line has been read.
  values.clear();
  for (const Assignment& a : block.assignments) values.push_back(a.value.evaluate(*this));
  for (std::size_t k = 0; k < block.assignments.size(); ++k) {
    const Assignment& a = block.assignments[k];
    if (a.named) {
      setNamedChecked(a.name, values[k]);
    } else {
      const double idx = a.index.evaluate(*this);
      setNumbered(toInt(idx, '#'), values[k]);
    }
  }
}

void Interpreter::Impl::checkWords(const ResolvedBlock& rb, const BlockCodes& c) const {
  const bool axis = rb.hasAxis();
  const int motion = c.motion >= 0 ? c.motion : st.motion;
  const bool arc = motion == 20 || motion == 30;
  const bool canned = motion >= 730 && motion != 800;
  const bool axis_user0 = c.non_modal == 100 || c.non_modal == 920 || c.non_modal == 520 ||
                          c.non_modal == 280 || c.non_modal == 300 || c.tlo == 431;
  if (axis_user0 && c.motion >= 0 && c.motion != 800 && axis)
    throw GcodeError(fmt::format("cannot use two G codes that both use axis values ({} and {})",
                                 gName(c.non_modal >= 0 ? c.non_modal : c.tlo),
                                 gName(c.motion)));
  if (axis && !axis_user0 && motion == 800)
    throw GcodeError(c.motion == 800 ? "cannot use axis values with G80"
                                     : "cannot use axis values without a G code that uses them "
                                       "(motion mode is G80)");
  if ((c.non_modal == 920 || c.non_modal == 520) && !axis)
    throw GcodeError(fmt::format("{} needs at least one axis word", gName(c.non_modal)));
  // An arc with I/J/K and no axis word is a full circle where the tool is (G2 I1, rs274).
  const bool arc_words = arc && c.non_modal != 100 && (axis || c.motion == 20 || c.motion == 30);
  const bool sync = motion == 330 || motion == 331;  // G33 K, G33.1 K (and I)
  if ((rb.hasWord('i') || rb.hasWord('j') || rb.hasWord('k')) && !arc_words && motion != 870 &&
      !sync)
    throw GcodeError("I, J or K word with no G2, G3 or G87 to use it");
  if (rb.hasWord('r') && !arc && !canned && c.non_modal != 100 && c.m_orient < 0)
    throw GcodeError("R word with no G2, G3, G10, M19 or canned cycle to use it");
  if (rb.hasWord('l') && !canned && c.non_modal != 100 && c.m_io != 66 && c.m_fanuc != 98 &&
      c.cutter != 411 && c.cutter != 421)
    throw GcodeError("L word with no G10, G41.1, G42.1, M66, M98 or canned cycle to use it");
  const bool io_q = c.m_io >= 66 || c.m_set_tool >= 0 || c.m_orient >= 0;
  if (rb.hasWord('q') && !(motion == 830 || motion == 730) && c.path != 640 && !io_q)
    throw GcodeError("Q word with no G73, G83, G64, M19, M61 or M66-M68 to use it");
  if (rb.hasWord('e') && c.m_io < 66) throw GcodeError("E word with no M66, M67 or M68 to use it");
  checkIoWords(rb, c);
  const bool dwell_cycle = motion == 740 || motion == 820 || motion == 840 || motion == 860 ||
                           motion == 880 || motion == 890;
  const bool io_p =
      (c.m_io >= 62 && c.m_io <= 66) || c.m_switch >= 0 || c.m_orient >= 0 || c.m_fanuc == 98;
  if (rb.hasWord('p') &&
      !(c.non_modal == 40 || c.non_modal == 100 || arc || dwell_cycle || c.path == 640 || io_p))
    throw GcodeError(
        "P word with no G4, G10, G2/G3, G64, M19, M50-M53, M62-M66 or dwelling canned cycle to "
        "use it");
  if (rb.hasWord('h') && c.tlo != 430) throw GcodeError("H word with no G43 to use it");
  if (rb.hasWord('d') && c.cutter < 410 && c.spindle_mode != 960)
    throw GcodeError("D word with no G41, G41.1, G42, G42.1 or G96 to use it");
  if (c.non_modal == 530 && !(motion == 0 || motion == 10))
    throw GcodeError("G53 needs G0 or G1 active");
  if (c.non_modal == 530 && (c.distance == 910 || (c.distance < 0 && st.incremental)))
    throw GcodeError("cannot use G53 in incremental distance mode");
  for (char l : {'u', 'v', 'w'})
    if (rb.hasWord(l)) throw GcodeError(fmt::format("{} axis is not supported", l));
}

void Interpreter::Impl::activeComment(const Block& block, MoveSink& sink) {
  const std::string text = block.comment == CommentKind::kMsg
                               ? block.comment_text
                               : substituteParameters(block.comment_text, *this);
  if (block.comment == CommentKind::kAbort) {
    const std::size_t first = text.find_first_not_of(" \t");
    throw GcodeError(
        fmt::format("program aborted: {}", first == std::string::npos ? "" : text.substr(first)));
  }
  // #5599 = 0 silences (DEBUG, ...) as in LinuxCNC (default 1).
  if (block.comment == CommentKind::kDebug && params.get(kDebugFlagParam) == 0.0) return;
  comp.message(block.line, block.comment, text, sink);
}

FanucRequest Interpreter::Impl::fanucRequest(const ResolvedBlock& rb, int m) const {
  FanucRequest r;
  r.kind = m;
  if (m == 99) return r;
  if (!rb.hasWord('p')) throw GcodeError("M98 needs a P word (the subprogram number)");
  const int p = toInt(rb.word('p'), 'P');
  if (p < 0) throw GcodeError("M98 P must be a subprogram number >= 0");
  r.target = std::to_string(p);
  if (rb.hasWord('l')) {
    const int l = toInt(rb.word('l'), 'L');
    if (l < 0) throw GcodeError("M98 L (the repeat count) must be >= 0");
    r.count = l;
  }
  return r;
}

void Interpreter::Impl::applyPolar(ResolvedBlock& rb) const {
  if (rb.hasWord('x') || rb.hasWord('y'))
    throw GcodeError("cannot give a polar coordinate (@, ^) and an X or Y word in one block");
  const Axes p = st.programPosition();
  const double x = p[0] / st.scale(), y = p[1] / st.scale();  // program units
  const double here_r = std::hypot(x, y);
  const double here_t = std::atan2(y, x) * kDegreesPerRadian;
  double r = rb.hasWord(kPolarRadius) ? rb.word(kPolarRadius) : 0.0;
  double t = rb.hasWord(kPolarAngle) ? rb.word(kPolarAngle) : 0.0;
  bool incremental = st.incremental;  // the block's own G90/G91 applies before its motion
  int motion = st.motion;
  for (int k = 0; k < rb.n_g; ++k) {
    const int g = rb.g[static_cast<std::size_t>(k)];
    if (g == 900) incremental = false;
    if (g == 910) incremental = true;
    if (g == 730 || g == 740 || (g >= 810 && g <= 890)) motion = g;
  }
  // A G91 canned cycle adds the polar words to each repeat's hole: cycle() takes them.
  if (incremental && (motion == 730 || motion == 740 || (motion >= 810 && motion <= 890))) return;
  if (incremental) {
    if (here_r == 0.0)
      throw GcodeError("G91 motion with polar coordinates is indeterminate at the origin");
    r += here_r;  // G91: the distance and angle are added to the point's own
    t += here_t;
  } else {
    if (!rb.hasWord(kPolarRadius)) r = here_r;
    if (!rb.hasWord(kPolarAngle)) t = here_t;
  }
  const double nx = r * std::cos(t / kDegreesPerRadian), ny = r * std::sin(t / kDegreesPerRadian);
  rb.value['x' - 'a'] = incremental ? nx - x : nx;
  rb.value['y' - 'a'] = incremental ? ny - y : ny;
  rb.has |= letterBit('x') | letterBit('y');
  rb.has &= ~(letterBit(kPolarRadius) | letterBit(kPolarAngle));
}

void Interpreter::Impl::checkToolExists(int tool) const {
  // LinuxCNC refuses a tool its table does not hold; without a table pkm knows no tools.
  if (tool != 0 && !options.tools.tools.empty() && options.tools.find(tool) == nullptr) {
    missing_tool = true;
    throw GcodeError(fmt::format("requested tool {} not found in the tool table", tool));
  }
}

void Interpreter::Impl::setFeedSpeedTool(const ResolvedBlock& rb, const BlockCodes& c) {
  if (c.feed_mode >= 0) {
    const bool inv = c.feed_mode == 930, per_rev = c.feed_mode == 950;
    if (inv != st.inverse_time || per_rev != st.feed_per_rev)
      st.feed = st.angular_feed = 0.0;  // LinuxCNC zeroes F on a change of feed mode
    st.inverse_time = inv;
    st.feed_per_rev = per_rev;
  }
  if (rb.hasWord('f')) {
    const double f = rb.word('f');
    if (f < 0.0) throw GcodeError("negative F word");
    if (!st.inverse_time) {
      st.feed = f * st.scale();
      st.angular_feed = f;
    }
  }
  if (c.spindle_mode >= 0) spindleMode(rb, c.spindle_mode);
  if (rb.hasWord('s')) {
    if (rb.word('s') < 0.0) throw GcodeError("negative spindle speed");
    st.spindle_speed = rb.word('s');
  }
  if (rb.hasWord('t')) {
    const int t = toInt(rb.word('t'), 'T');
    if (t < 0) throw GcodeError("negative tool number");
    checkToolExists(t);
    st.selected_tool = t;
  }
  if (c.m_tool == 6) {
    st.tool_in_spindle = st.selected_tool;
    if (const ToolEntry* t = options.tools.find(st.tool_in_spindle)) spindle_entry = t->offset;
  }
  if (c.m_set_tool >= 0) {
    const int t = toInt(rb.word('q'), 'Q');
    if (t < 0) throw GcodeError("M61 needs a tool number Q >= 0");
    checkToolExists(t);
    st.tool_in_spindle = t;
  }
}

bool Interpreter::Impl::execute(const Block& block, MoveSink& sink) {
  current_line = block.line;
  if (!block.deferred_error.empty()) throw GcodeError(block.deferred_error);
  ResolvedBlock rb;
  resolve(block, rb, sink);
  if (block.comment != CommentKind::kNone) activeComment(block, sink);
  if ((rb.has & (letterBit(kPolarRadius) | letterBit(kPolarAngle))) != 0) applyPolar(rb);
  if (rb.n_g == 0 && rb.n_m == 0 && !rb.hasAxis() && !rb.hasWord('f') && !rb.hasWord('s') &&
      !rb.hasWord('t')) {
    for (char l : {'i', 'j', 'k', 'r', 'l', 'p', 'q', 'h', 'd', 'e', 'u', 'v', 'w'})
      if (rb.hasWord(l)) throw GcodeError(fmt::format("{} word with nothing to use it", l));
    return true;
  }
  const BlockCodes c = classify(rb);
  checkWords(rb, c);
  checkCompRestrictions(rb, c);
  setFeedSpeedTool(rb, c);
  if (c.m_override >= 0) st.overrides_enabled = c.m_override == 48;
  if (c.m_mist) st.mist = true;
  if (c.m_flood) st.flood = true;
  if (c.m_coolant_off) st.mist = st.flood = false;
  if (c.m_spindle >= 0) st.spindle_direction = c.m_spindle == 3 ? 1 : c.m_spindle == 4 ? -1 : 0;
  if (c.m_modes >= 0) modalState(c.m_modes);
  if (c.non_modal == 40) {
    if (!rb.hasWord('p')) throw GcodeError("G4 needs a P word (dwell time, s)");
    if (rb.word('p') < 0.0) throw GcodeError("negative G4 dwell time");
    comp.dwell(rb.line, rb.word('p'), sink);
  }
  if (c.plane >= 0)
    st.plane = c.plane == 170 ? Plane::kXY : c.plane == 180 ? Plane::kXZ : Plane::kYZ;
  if (c.units >= 0) st.inch = c.units == 200;
  if (c.cutter >= 0) cutterCompensation(rb, c.cutter, sink);
  if (c.tlo >= 0) setTlo(rb, c.tlo);
  if (c.wcs >= 0) {
    static constexpr std::array<int, 9> kCodes{540, 550, 560, 570, 580, 590, 591, 592, 593};
    for (std::size_t n = 0; n < kCodes.size(); ++n)
      if (kCodes[n] == c.wcs) selectSystem(static_cast<int>(n) + 1);
  }
  if (c.path >= 0) st.path_mode = c.path;
  if (c.distance >= 0) st.incremental = c.distance == 910;
  if (c.ijk >= 0) st.ijk_absolute = c.ijk == 901;
  if (c.retract >= 0) st.retract_to_r = c.retract == 990;
  if (c.non_modal == 100) doG10(rb);
  if (c.non_modal >= 920 || c.non_modal == 520) doG92(rb, c.non_modal);
  if (c.non_modal >= 280 && c.non_modal <= 301) doHome(rb, c.non_modal, sink);
  if (st.tool_in_spindle != reported_tool) {
    reported_tool = st.tool_in_spindle;
    sink.onToolChange(rb.line, reported_tool);
  }
  const std::size_t moves_before = summary.moves;
  doMotion(rb, c, sink);
  if (c.m_fanuc >= 0) fanuc = fanucRequest(rb, c.m_fanuc);
  if (c.m_tool == 6 && summary.moves == moves_before) {
    // After a tool change rs274 re-reads the position in program coordinates as the last motion
    // left it (tool offset changes since then do not count), so a G43/G49 since that motion
    // shifts the machine position the next motion starts its unprogrammed axes from (checked
    // with rs274: "T1 M6 G43 H1" then "G0 X1" moves Z).
    // Cutter compensation may have left the tool off the programmed path: rs274 re-reads it.
    if (const Axes* tool = comp.displacedTool()) st.machine = *tool;
    for (std::size_t i = 0; i < 6; ++i) st.machine[i] += st.tool_offset[i] - tlo_at_last_motion[i];
    tlo_at_last_motion = st.tool_offset;
  }
  if (c.m_stop >= 0) flushCompensation(sink);  // M0, M1, M2, M30, M60
  return !(c.m_stop == 2 || c.m_stop == 30);
}

}  // namespace pkm::cnc
