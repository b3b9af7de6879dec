#include "pkm/cnc/program_compensation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cctype>
#include <cmath>
#include <map>
#include <optional>
#include <set>

#include "pkm/cnc/flatten.hpp"
#include "pkm/cnc/gcode_error.hpp"
#include "pkm/cnc/interpreter.hpp"
#include "pkm/cnc/joint_path.hpp"
#include "pkm/cnc/program.hpp"
#include "pkm/core/error.hpp"

namespace pkm::cnc {
namespace {

[[noreturn]] void fail(const std::string& file, std::size_t line, const std::string& what) {
  throw IoError(fmt::format("{}:{}: {}", file, line, what));
}

/// G words (×10) the rewrite cannot express: G87 (spindle orientation, M19, which the
/// interpreter does not run), G88 (the operator retracts by hand, so the rewritten program would
/// not know where the tool is), probing, spindle-synchronised motion, and inverse time (a feed
/// per source motion).
bool unsupportedG(long g10) {
  static constexpr long kBad[] = {870, 880, 930, 382, 383, 384, 385, 330, 331, 760};
  return std::find(std::begin(kBad), std::end(kBad), g10) != std::end(kBad);
}

/// The codes (G number) that are expanded into G0/G1 lines, G4 dwells and M codes: the drilling,
/// tapping and boring cycles, and G28/G30 (the rapids to the intermediate point and to the stored
/// position).
bool cycleG(double g) {
  return g == 73.0 || g == 74.0 || g == 81.0 || g == 82.0 || g == 83.0 || g == 84.0 || g == 85.0 ||
         g == 86.0 || g == 89.0 || g == 28.0 || g == 30.0;
}

/// The block that does a canned cycle's action, with a "{}" for the source line.
const char* actionBlock(CycleAction a) {
  switch (a) {
    case CycleAction::kSpindleStop:
      return "M5 (pkm: line {} spindle stop)";
    case CycleAction::kSpindleClockwise:
      return "M3 (pkm: line {} spindle clockwise)";
    case CycleAction::kSpindleCounterClockwise:
      return "M4 (pkm: line {} spindle counter-clockwise)";
    case CycleAction::kOverridesOff:
      return "M49 (pkm: line {} overrides off)";
    case CycleAction::kOverridesOn:
      return "M48 (pkm: line {} overrides on)";
    case CycleAction::kSpindleOrient:  // G87, G88: refused by checkBlock
    case CycleAction::kProgramStop:
      break;
  }
  return "(pkm: line {} unsupported cycle action)";
}

struct NoParams final : ParameterSource {
  double numbered(int) override { return 0.0; }
  double named(const std::string&) override { return 0.0; }
  bool exists(const std::string&) override { return false; }
};

/// A G92 or G10 L20 line: it sets an offset so that the *current* position reads as the given
/// values. On the pre-distorted machine the current position is the last command, not the
/// desired point, so each value is shifted by (command − desired)/scale to give the same offset.
struct OffsetLine {
  std::array<std::optional<double>, 6> values{};  ///< X Y Z A B C as written (program units)
  double scale = 1.0;                             ///< mm per program length unit on that line
};

/// The subset's checks and what the rewrite needs from the blocks (one pass in program order:
/// without O-words that is the order of execution).
struct BlockScan {
  std::set<std::size_t> g53_lines;
  std::map<std::size_t, OffsetLine> offset_lines;
  double scale = 1.0;  ///< G20/G21 state while scanning
};

/// Rejects blocks outside the supported subset (see the header); notes G53 and offset lines.
void checkBlock(const Block& b, const std::string& file, BlockScan& scan) {
  if (b.o_kind != OKind::kNone) fail(file, b.line, "gcode compensate does not support O-words");
  NoParams params;
  bool sets_offset = false;
  for (const Word& w : b.words) {
    if (w.letter != 'g') continue;
    if (!w.value.isConstant()) fail(file, b.line, "gcode compensate needs constant G words");
    const long g10 = std::lround(w.value.evaluate(params) * 10.0);
    if (g10 == 530) scan.g53_lines.insert(b.line);
    if (g10 == 200) scan.scale = 25.4;
    if (g10 == 210) scan.scale = 1.0;
    const bool l20 = std::any_of(b.words.begin(), b.words.end(), [&](const Word& x) {
      return x.letter == 'l' && x.value.isConstant() && x.value.evaluate(params) == 20.0;
    });
    sets_offset = sets_offset || g10 == 920 || (g10 == 100 && l20);
    if (unsupportedG(g10))
      fail(file,
           b.line,
           fmt::format("G{} is not supported by gcode compensate (it rewrites one motion per "
                       "line, or expands a canned cycle or G28/G30: no G87/G88, probing, G33/G76 "
                       "or G93)",
                       static_cast<double>(g10) / 10.0));
  }
  if (!sets_offset) return;
  OffsetLine o;
  static constexpr std::string_view kAxes = "xyzabc";
  for (const Word& w : b.words) {
    const std::size_t k = kAxes.find(w.letter);
    if (k == std::string_view::npos) continue;
    if (!w.value.isConstant())
      fail(file,
           b.line,
           "gcode compensate needs constant axis words on a G92 or G10 L20 line (their values "
           "are shifted by the correction at the current position)");
    o.values[k] = w.value.evaluate(params);
  }
  o.scale = scan.scale;  // G20/G21 act before G10 and G92 within a block
  scan.offset_lines[b.line] = o;
}

/// Appends letter and `nano` / 1e9 with up to 9 decimals, trailing zeros dropped (from the
/// integer, so incremental words add up exactly to the absolute values they stand for).
void appendCoord(std::string& out, char letter, long long nano) {
  out.push_back(letter);
  if (nano < 0) out.push_back('-');
  const unsigned long long a = nano < 0 ? 0ull - static_cast<unsigned long long>(nano)
                                        : static_cast<unsigned long long>(nano);
  out += std::to_string(a / 1000000000ull);
  unsigned long long frac = a % 1000000000ull;
  if (frac == 0) {
    if (a == 0 && nano < 0) out.pop_back();  // no "-0"
    return;
  }
  char digits[9];
  for (int i = 8; i >= 0; --i, frac /= 10) digits[i] = static_cast<char>('0' + frac % 10);
  int len = 9;
  while (digits[len - 1] == '0') --len;
  out.push_back('.');
  out.append(digits, static_cast<std::size_t>(len));
}

/// What the axis words of a motion's line mean: program = (machine − offset) / scale (scale 25.4
/// for the lengths under G20, 1 for angles), absolute or relative to the previous position.
struct WordFrame {
  Axes offset{};
  double scale = 1.0;
  bool incremental = false;
  bool machine = false;  ///< G53 (non-modal: repeated on the inserted segment lines)
};

/// A value in program units, in nano-units (1e-9) as written.
long long nanoUnits(const Axes& machine, const WordFrame& f, std::size_t k) {
  const double v = (machine[k] - f.offset[k]) / (k < 3 ? f.scale : 1.0);
  return std::llround(v * 1e9);
}

/// The six axis words that command machine position `c` from `previous` (the last commanded
/// machine position) under `f`.
std::string axisWords(const Axes& c,
                      const Axes& previous,
                      const WordFrame& f,
                      const AxisMask& axes) {
  std::string s;
  static constexpr char kLetters[] = {'X', 'Y', 'Z', 'A', 'B', 'C'};
  for (std::size_t k = 0; k < 6; ++k) {
    if (!axes[k]) continue;
    if (!s.empty()) s.push_back(' ');
    const long long v = nanoUnits(c, f, k);
    appendCoord(s, kLetters[k], f.incremental ? v - nanoUnits(previous, f, k) : v);
  }
  return s;
}

/// A block inserted after a motion of an expanded cycle: a dwell or a cycle action.
struct CycleEvent {
  std::size_t line = 0;         ///< source line (the cycle's)
  std::size_t after_moves = 0;  ///< motions made before it
  std::string text;             ///< the block
};

/// Collects the motions with the word frame in effect when each was made, and the dwells and
/// cycle actions.
class FrameSink final : public MoveSink {
 public:
  explicit FrameSink(const Interpreter& interpreter) : interpreter_(&interpreter) {}
  void onMove(const Move& move) override {
    moves.push_back(move);
    const MachineState& st = interpreter_->state();
    WordFrame f;
    for (std::size_t k = 0; k < 6; ++k) f.offset[k] = st.offset(k);
    f.scale = st.scale();
    f.incremental = st.incremental;
    frames.push_back(f);
  }
  void onDwell(std::size_t line, double seconds) override {
    std::string w = "G4 ";
    appendCoord(w, 'P', std::llround(seconds * 1e9));
    events.push_back({line, moves.size(), fmt::format("{} (pkm: line {} dwell)", w, line)});
  }
  void onCycleAction(std::size_t line, CycleAction action) override {
    events.push_back({line, moves.size(), fmt::format(fmt::runtime(actionBlock(action)), line)});
  }
  std::vector<Move> moves;
  std::vector<WordFrame> frames;
  std::vector<CycleEvent> events;

 private:
  const Interpreter* interpreter_;
};

/// What rewriteLine replaces: a line's motion (G0..G3 and X..C, I J K R, P of an arc; the new
/// words go after the N word), a drilling cycle (also its G word and R, Q, P, L), or the axis
/// words of a G92/G10 L20 line (X..C only; the new words go where the first of them was).
enum class Rewrite { kMotion, kArc, kCycle, kOffset };

/// The line with the words `what` names removed and `words` inserted; comments, blanks and
/// other words stay where they are.
std::string rewriteLine(std::string_view line, Rewrite what, const std::string& words) {
  const bool arc = what == Rewrite::kArc, offset = what == Rewrite::kOffset,
             cycle = what == Rewrite::kCycle;
  std::size_t first_drop = std::string::npos;
  std::string out;
  std::size_t insert_at = std::string::npos;
  std::size_t i = 0;
  const std::size_t n = line.size();
  while (i < n) {
    const char ch = line[i];
    if (ch == '(') {
      const std::size_t close = line.find(')', i);
      const std::size_t end = close == std::string_view::npos ? n : close + 1;
      out.append(line.substr(i, end - i));
      i = end;
      continue;
    }
    if (ch == ';') {
      out.append(line.substr(i));
      break;
    }
    if (!std::isalpha(static_cast<unsigned char>(ch)) && ch != '#') {
      out.push_back(ch);
      ++i;
      continue;
    }
    // A word or parameter setting: its value spans blanks up to the next word or comment. The
    // compact text (no blanks, lower case) is parsed with the interpreter's own reader.
    std::string compact;
    std::vector<std::size_t> where;
    for (std::size_t j = i; j < n && line[j] != '(' && line[j] != ';'; ++j) {
      if (line[j] == ' ' || line[j] == '\t' || line[j] == '\r') continue;
      compact.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(line[j]))));
      where.push_back(j);
    }
    std::size_t pos = ch == '#' ? 0 : 1;
    (void)Expression::parseReal(compact, pos);
    if (ch == '#') {  // #n = value
      ++pos;
      (void)Expression::parseReal(compact, pos);
    }
    const std::size_t end = where[pos - 1] + 1;
    const char l = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    bool drop =
        std::string_view(offset ? "xyzabc" : "xyzabcijkr").find(l) != std::string_view::npos ||
        (arc && l == 'p') || (cycle && std::string_view("pql").find(l) != std::string_view::npos);
    if (l == 'g' && !offset) {
      std::size_t p = 1;
      const Expression e = Expression::parseReal(compact, p);
      if (e.isConstant()) {
        NoParams params;
        const double g = e.evaluate(params);
        drop = g == 0.0 || g == 1.0 || g == 2.0 || g == 3.0 || (cycle && cycleG(g));
      }
    }
    if (l == 'n') {
      out.append(line.substr(i, end - i));
      insert_at = out.size();
    } else if (!drop) {
      out.append(line.substr(i, end - i));
    } else if (first_drop == std::string::npos) {
      first_drop = out.size();
    }
    i = end;
    if (drop)  // the blanks after a removed word go with it
      while (i < n && (line[i] == ' ' || line[i] == '\t')) ++i;
  }
  // No trailing blanks that the source line did not have.
  const bool blank_end = !line.empty() && (line.back() == ' ' || line.back() == '\t');
  while (!blank_end && !out.empty() && (out.back() == ' ' || out.back() == '\t')) out.pop_back();
  if (offset && first_drop != std::string::npos) {
    if (first_drop < out.size()) {
      out.insert(first_drop, words + " ");
    } else {  // the axis words ended the line (its trailing blanks are gone)
      const bool blank = out.empty() || out.back() == ' ' || out.back() == '\t';
      out += blank ? words : " " + words;
    }
  } else if (insert_at == std::string::npos) {
    // After a block-delete slash and leading blanks.
    insert_at = 0;
    while (insert_at < out.size() &&
           (out[insert_at] == ' ' || out[insert_at] == '\t' || out[insert_at] == '/'))
      ++insert_at;
    out.insert(insert_at, insert_at < out.size() ? words + " " : words);
  } else {
    out.insert(insert_at, " " + words);
  }
  return out;
}

/// "FILE:K: message" about line K of the flattened program, told of its source line.
IoError onSourceLine(const IoError& e, const std::string& file, const FlatProgram& flat) {
  const std::string what = e.what();
  const std::string prefix = file + ":";
  std::size_t k = 0;
  std::size_t pos = prefix.size();
  if (what.compare(0, prefix.size(), prefix) != 0) return e;
  while (pos < what.size() && std::isdigit(static_cast<unsigned char>(what[pos])))
    k = k * 10 + static_cast<std::size_t>(what[pos++] - '0');
  if (k == 0 || k > flat.source_line.size() || what.compare(pos, 2, ": ") != 0) return e;
  return IoError(fmt::format("{}:{}: {} (line {} of the flattened program)",
                             file,
                             flat.source_line[k - 1],
                             what.substr(pos + 2),
                             k));
}

ProgramCompensation rewriteFlat(std::string_view text,
                                const std::string& file,
                                const Program& program,
                                const PointMap& map,
                                const InterpolationOptions& interpolation,
                                const AxisMask& axes,
                                const InterpreterOptions& interpreter_options) {
  BlockScan scan;
  for (const Block& b : program.blocks()) checkBlock(b, file, scan);
  const std::set<std::size_t>& g53_lines = scan.g53_lines;
  Interpreter interpreter(interpreter_options);
  FrameSink moves(interpreter);
  (void)interpreter.run(program, moves);
  // G53 words are machine coordinates (absolute, no offsets; in the program's length unit).
  for (std::size_t m = 0; m < moves.moves.size(); ++m)
    if (g53_lines.count(moves.moves[m].line) != 0) {
      moves.frames[m].offset = Axes{};
      moves.frames[m].incremental = false;
      moves.frames[m].machine = true;
    }
  // The interpolated points of each line's motions: one motion, or the consecutive motions of a
  // drilling cycle.
  std::map<std::size_t, std::pair<std::size_t, std::size_t>> span;  // line -> [first, last)
  std::map<std::size_t, std::size_t> motions_of_line;
  std::vector<PathPoint> points;
  PathInterpolator interp(interpolation, moves.moves.empty() ? Axes{} : moves.moves.front().end);
  for (std::size_t m = 0; m < moves.moves.size(); ++m) {
    const Move& mv = moves.moves[m];
    const auto it = span.find(mv.line);
    if (it != span.end() && it->second.second != points.size())
      fail(file, mv.line, "gcode compensate needs the motions of a line to be consecutive");
    const std::size_t first = it == span.end() ? points.size() : it->second.first;
    try {
      interp.append(mv, static_cast<std::uint32_t>(m), points);
    } catch (const PathTooLong& e) {
      fail(file, mv.line, fmt::format("{}: raise it with --max-points N", e.what()));
    }
    span[mv.line] = {first, points.size()};
    ++motions_of_line[mv.line];
  }
  // Dwells and actions of multi-motion lines (a G4 line is copied as it is).
  std::map<std::size_t, std::vector<CycleEvent>> cycle_events;
  for (const CycleEvent& d : moves.events) {
    const auto n = motions_of_line.find(d.line);
    if (n == motions_of_line.end() || n->second < 2) continue;
    if (d.after_moves == 0 || moves.moves[d.after_moves - 1].line != d.line)
      fail(file, d.line, "gcode compensate does not support G4 on a canned-cycle line");
    cycle_events[d.line].push_back(d);
  }
  const std::vector<Axes> commands = map(points);
  assert(commands.size() == points.size());
  ProgramCompensation r;
  r.points.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    CompensatedPoint& cp = r.points[i];
    cp.line = points[i].line;
    cp.desired = points[i].pos;
    cp.command = commands[i];
    r.max_correction = std::max(r.max_correction,
                                std::hypot(cp.command[0] - cp.desired[0],
                                           cp.command[1] - cp.desired[1],
                                           cp.command[2] - cp.desired[2]));
  }
  // Rewrite line by line; line numbers are 1-based as in Program.
  std::size_t line_no = 0, start = 0, next_point = 0;
  r.text.reserve(text.size() + text.size() / 2);
  while (start < text.size()) {
    ++line_no;
    std::size_t nl = text.find('\n', start);
    const bool has_nl = nl != std::string_view::npos;
    if (!has_nl) nl = text.size();
    std::string_view line = text.substr(start, nl - start);
    const auto it = span.find(line_no);
    const auto off = scan.offset_lines.find(line_no);
    if (off != scan.offset_lines.end()) {
      // The correction at the current position: that of the last point before this line.
      while (next_point < r.points.size() && r.points[next_point].line < line_no) ++next_point;
      Axes delta{};
      if (next_point > 0) {
        const CompensatedPoint& cp = r.points[next_point - 1];
        for (std::size_t k = 0; k < 6; ++k) delta[k] = cp.command[k] - cp.desired[k];
      }
      std::string words;
      static constexpr char kLetters[] = {'X', 'Y', 'Z', 'A', 'B', 'C'};
      for (std::size_t k = 0; k < 6; ++k) {
        const auto& v = off->second.values[k];
        if (!v) continue;
        if (!words.empty()) words.push_back(' ');
        const double shifted = *v + delta[k] / (k < 3 ? off->second.scale : 1.0);
        appendCoord(words, kLetters[k], std::llround(shifted * 1e9));
      }
      const bool cr = !line.empty() && line.back() == '\r';
      if (cr) line.remove_suffix(1);
      r.text += rewriteLine(line, Rewrite::kOffset, words);
      if (cr) r.text.push_back('\r');
      if (has_nl) r.text.push_back('\n');
      ++r.offset_lines;
    } else if (it == span.end()) {
      r.text.append(line);
      if (has_nl) r.text.push_back('\n');
    } else {
      const std::size_t first = it->second.first, last = it->second.second;
      const PathPoint& p0 = points[first];
      const bool cycle = motions_of_line[line_no] > 1;
      // The previous commanded position: the interpreter's start-up position before the first.
      const auto previous = [&](std::size_t k) {
        return k == 0 ? Axes{} : r.points[k - 1].command;
      };
      const auto gWord = [&](std::size_t k) {
        return points[k].kind == MoveKind::kRapid ? "G0 " : "G1 ";
      };
      const auto words = [&](std::size_t k) {
        return axisWords(r.points[k].command, previous(k), moves.frames[points[k].move], axes);
      };
      const bool cr = !line.empty() && line.back() == '\r';
      if (cr) line.remove_suffix(1);
      const std::string eol = cr ? "\r\n" : "\n";
      const Rewrite kind = cycle                       ? Rewrite::kCycle
                           : p0.kind == MoveKind::kArc ? Rewrite::kArc
                                                       : Rewrite::kMotion;
      r.text += rewriteLine(line, kind, gWord(first) + words(first));
      ++r.motion_lines;
      std::vector<std::string> inserted;
      const auto eventsAfter = [&](std::size_t k) {
        if (!cycle || (k + 1 < last && points[k + 1].move == points[k].move)) return;
        for (const CycleEvent& d : cycle_events[line_no])
          if (d.after_moves == points[k].move + 1u) {
            inserted.push_back(d.text);
            ++r.added_lines;
          }
      };
      eventsAfter(first);
      for (std::size_t k = first + 1; k < last; ++k) {
        inserted.push_back(fmt::format("{}{}{} (pkm: line {} segment {}/{})",
                                       moves.frames[points[k].move].machine ? "G53 " : "",
                                       gWord(k),
                                       words(k),
                                       line_no,
                                       k - first + 1,
                                       last - first));
        ++r.added_lines;
        eventsAfter(k);
      }
      for (const std::string& s : inserted) r.text += eol + s;
      if (has_nl) r.text += eol;
    }
    start = nl + 1;
  }
  return r;
}

}  // namespace

ProgramCompensation rewriteProgram(std::string_view text,
                                   const std::string& file,
                                   const PointMap& map,
                                   const InterpolationOptions& interpolation,
                                   const AxisMask& axes,
                                   const InterpreterOptions& interpreter) {
  const Program program = Program::parse(text, file);
  const bool o_words = std::any_of(program.blocks().begin(),
                                   program.blocks().end(),
                                   [](const Block& b) { return b.o_kind != OKind::kNone; });
  if (!o_words) return rewriteFlat(text, file, program, map, interpolation, axes, interpreter);
  // Subroutines and loops: rewrite the blocks as executed (docs/gcode.md "gcode flatten").
  const FlatProgram flat = flattenProgram(text, file, interpreter);
  try {
    ProgramCompensation r = rewriteFlat(
        flat.text, file, Program::parse(flat.text, file), map, interpolation, axes, interpreter);
    r.flattened_blocks = flat.blocks;
    return r;
  } catch (const IoError& e) {
    throw onSourceLine(e, file, flat);
  }
}

ProgramCompensation compensateProgram(std::string_view text,
                                      const std::string& file,
                                      const kinematics::HexapodModel& nominal,
                                      const kinematics::HexapodModel& calibrated,
                                      const ProgramCompensationOptions& options) {
  const PointMap map = [&](const std::vector<PathPoint>& points) {
    std::vector<kinematics::PoseRpy> desired(points.size());
    for (std::size_t i = 0; i < points.size(); ++i)
      desired[i] = poseFromAxes(points[i].pos, calibrated.unit);
    const auto results =
        compensation::predistortPath(nominal, calibrated, desired, options.predistortion);
    const double mm = millimetresPer(nominal.unit);
    std::vector<Axes> commands(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (!results[i].ok())
        fail(file,
             points[i].line,
             "the nominal forward kinematics did not converge for this motion");
      const auto& c = results[i].command;
      commands[i] = {c.position.x() * mm,
                     c.position.y() * mm,
                     c.position.z() * mm,
                     radToDeg(c.rpy.x()),
                     radToDeg(c.rpy.y()),
                     radToDeg(c.rpy.z())};
    }
    return commands;
  };
  return rewriteProgram(text, file, map, options.interpolation, kAllAxes, options.interpreter);
}

ProgramCompensation compensateHybridProgram(std::string_view text,
                                            const std::string& file,
                                            const compensation::HybridSquarenessCompensation& c,
                                            double x2,
                                            bool base_frame_in_controller,
                                            const InterpolationOptions& interpolation,
                                            const InterpreterOptions& interpreter) {
  PKM_CHECK(std::isfinite(x2), "the X2 position must be finite, got {}", x2);
  const PointMap map = [&](const std::vector<PathPoint>& points) {
    std::vector<Axes> commands(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector3d p(points[i].pos[0], points[i].pos[1], points[i].pos[2]);
      const Eigen::Vector3d q =
          (base_frame_in_controller ? p : Eigen::Vector3d(c.base_rotation * p + c.base_offset)) +
          x2 * c.per_x2;
      commands[i] = {q.x(), q.y(), q.z(), points[i].pos[3], points[i].pos[4], points[i].pos[5]};
    }
    return commands;
  };
  return rewriteProgram(text, file, map, interpolation, kAllAxes, interpreter);
}

}  // namespace pkm::cnc
