#include "pkm/cnc/program_compensation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cassert>
#include <cctype>
#include <cmath>
#include <map>
#include <set>

#include "pkm/cnc/flatten.hpp"
#include "pkm/cnc/gcode_error.hpp"
#include "pkm/cnc/interpreter.hpp"
#include "pkm/cnc/joint_path.hpp"
#include "pkm/cnc/program.hpp"
#include "pkm/core/error.hpp"
#include "program_rewrite.hpp"

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
  static constexpr long kBad[] = {870, 880, 930, 382, 383, 384, 385, 330, 331, 760, 520};
  return std::find(std::begin(kBad), std::end(kBad), g10) != std::end(kBad);
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

/// The subset's checks and what the rewrite needs from the blocks (one pass in program order:
/// without O-words that is the order of execution).
struct BlockScan {
  std::set<std::size_t> g53_lines;
  std::map<std::size_t, detail::OffsetLine> offset_lines;
  double scale = 1.0;                ///< G20/G21 state while scanning
  bool comp_on = false;              ///< G41/G42/G41.1/G42.1 in effect (until G40)
  std::set<std::size_t> comp_lines;  ///< lines with G41/G42/G41.1/G42.1 (their words go)
};

/// Cutter compensation in a program to rewrite: the written motions are the compensated path,
/// so the compensation words go (RewriteInput::comp_lines). A change of units, distance mode or
/// tool length offset while compensation is on is refused: a move's end is held until the next
/// block, whose modes would then write it.
void scanCutterComp(const Block& b, const std::string& file, BlockScan& scan) {
  detail::NoParams params;
  bool units = false, modes = false, on = scan.comp_on, off = false;
  for (const Word& w : b.words) {
    if (w.letter != 'g' || !w.value.isConstant()) continue;
    const long g10 = std::lround(w.value.evaluate(params) * 10.0);
    units = units || g10 == 200 || g10 == 210;
    modes = modes || g10 == 900 || g10 == 910 || g10 == 430 || g10 == 431 || g10 == 490;
    if (g10 == 410 || g10 == 420 || g10 == 411 || g10 == 421) {
      on = true;
      scan.comp_lines.insert(b.line);
    }
    off = off || g10 == 400;
  }
  if ((units && scan.comp_on) || (modes && on && !off))
    fail(file,
         b.line,
         "gcode compensate does not support changing units, distance mode or tool length offset "
         "while cutter radius compensation is on");
  scan.comp_on = on && !off;
}

/// Rejects blocks outside the supported subset (see the header); notes G53 and offset lines.
void checkBlock(const Block& b, const std::string& file, BlockScan& scan) {
  if (b.o_kind != OKind::kNone) fail(file, b.line, "gcode compensate does not support O-words");
  scanCutterComp(b, file, scan);
  detail::NoParams params;
  bool sets_offset = false;
  for (const Word& w : b.words)
    if (w.letter == kPolarRadius || w.letter == kPolarAngle)
      fail(file, b.line, "gcode compensate does not support polar coordinates (@, ^)");
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
    const bool tool_from_position = std::any_of(b.words.begin(), b.words.end(), [&](const Word& x) {
      return x.letter == 'l' && x.value.isConstant() &&
             (x.value.evaluate(params) == 10.0 || x.value.evaluate(params) == 11.0);
    });
    if (g10 == 100 && tool_from_position)
      fail(file,
           b.line,
           "gcode compensate does not support G10 L10/L11: they set a tool entry from the "
           "position, which the compensated program changes");
    sets_offset = sets_offset || g10 == 920 || (g10 == 100 && l20);
    if (unsupportedG(g10))
      fail(file,
           b.line,
           fmt::format("G{} is not supported by gcode compensate (it rewrites one motion per "
                       "line, or expands a canned cycle or G28/G30: no G87/G88, probing, G33/G76, "
                       "G52 or G93)",
                       static_cast<double>(g10) / 10.0));
  }
  if (!sets_offset) return;
  detail::OffsetLine o;
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

/// Collects the motions with the word frame in effect when each was made, and the dwells and
/// cycle actions.
class FrameSink final : public MoveSink {
 public:
  explicit FrameSink(const Interpreter& interpreter) : interpreter_(&interpreter) {}
  void onMove(const Move& move) override {
    moves.push_back(move);
    const MachineState& st = interpreter_->state();
    detail::WordFrame f;
    if (st.rotation != 0.0)  // the rewritten words would need the rotation undone
      throw GcodeError(
          "gcode compensate does not support a rotated coordinate system (G10 L2 R); the "
          "program was not written");
    for (std::size_t k = 0; k < 6; ++k) f.offset[k] = st.g5x[k] + st.g92[k] + st.tool_offset[k];
    f.scale = st.scale();
    f.incremental = st.incremental;
    frames.push_back(f);
  }
  void onDwell(std::size_t line, double seconds) override {
    std::string w = "G4 ";
    detail::appendCoord(w, 'P', std::llround(seconds * 1e9));
    events.push_back({line, moves.size(), fmt::format("{} (pkm: line {} dwell)", w, line)});
  }
  void onCycleAction(std::size_t line, CycleAction action) override {
    events.push_back({line, moves.size(), fmt::format(fmt::runtime(actionBlock(action)), line)});
  }
  std::vector<Move> moves;
  std::vector<detail::WordFrame> frames;
  std::vector<detail::CycleEvent> events;

 private:
  const Interpreter* interpreter_;
};

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

/// Marks the motions of G53 lines: their words are machine coordinates (absolute, no offsets;
/// in the program's length unit).
void markMachineFrames(FrameSink& moves, const std::set<std::size_t>& g53_lines) {
  for (std::size_t m = 0; m < moves.moves.size(); ++m)
    if (g53_lines.count(moves.moves[m].line) != 0) {
      moves.frames[m].offset = Axes{};
      moves.frames[m].incremental = false;
      moves.frames[m].machine = true;
    }
}

/// Interpolates `moves` by `interpolation` line by line; throws IoError "FILE:LINE: ..." when
/// the motions of a line are not consecutive or the path has too many points.
detail::LineSpans interpolateLines(const std::vector<Move>& moves,
                                   const InterpolationOptions& interpolation,
                                   const std::string& file) {
  detail::LineSpans s;
  PathInterpolator interp(interpolation, moves.empty() ? Axes{} : moves.front().end);
  for (std::size_t m = 0; m < moves.size(); ++m) {
    const Move& mv = moves[m];
    const auto it = s.span.find(mv.line);
    if (it != s.span.end() && it->second.second != s.points.size())
      fail(file, mv.line, "gcode compensate needs the motions of a line to be consecutive");
    const std::size_t first = it == s.span.end() ? s.points.size() : it->second.first;
    try {
      interp.append(mv, static_cast<std::uint32_t>(m), s.points);
    } catch (const PathTooLong& e) {
      fail(file, mv.line, fmt::format("{}: raise it with --max-points N", e.what()));
    }
    s.span[mv.line] = {first, s.points.size()};
    ++s.motions_of_line[mv.line];
  }
  return s;
}

/// The dwells and actions of multi-motion lines, by line (a G4 line is copied as it is); throws
/// IoError for a G4 on a canned-cycle line.
std::map<std::size_t, std::vector<detail::CycleEvent>> cycleEventsByLine(
    const FrameSink& moves,
    const std::map<std::size_t, std::size_t>& motions_of_line,
    const std::string& file) {
  std::map<std::size_t, std::vector<detail::CycleEvent>> cycle_events;
  for (const detail::CycleEvent& d : moves.events) {
    const auto n = motions_of_line.find(d.line);
    if (n == motions_of_line.end() || n->second < 2) continue;
    if (d.after_moves == 0 || moves.moves[d.after_moves - 1].line != d.line)
      fail(file, d.line, "gcode compensate does not support G4 on a canned-cycle line");
    cycle_events[d.line].push_back(d);
  }
  return cycle_events;
}

/// Fills r.points from the interpolated points and their commands (mm, degrees) and
/// r.max_correction, the largest |command − desired| in XYZ.
void fillCompensatedPoints(ProgramCompensation& r,
                           const std::vector<PathPoint>& points,
                           const std::vector<Axes>& commands) {
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
}

/// rewriteProgram for a program without O-words (`program` is `text` parsed).
ProgramCompensation rewriteFlat(std::string_view text,
                                const std::string& file,
                                const Program& program,
                                const PointMap& map,
                                const InterpolationOptions& interpolation,
                                const AxisMask& axes,
                                const InterpreterOptions& interpreter_options) {
  BlockScan scan;
  for (const Block& b : program.blocks()) checkBlock(b, file, scan);
  Interpreter interpreter(interpreter_options);
  FrameSink moves(interpreter);
  (void)interpreter.run(program, moves);
  markMachineFrames(moves, scan.g53_lines);
  detail::LineSpans lines = interpolateLines(moves.moves, interpolation, file);
  std::map<std::size_t, std::vector<detail::CycleEvent>> cycle_events =
      cycleEventsByLine(moves, lines.motions_of_line, file);
  const std::vector<Axes> commands = map(lines.points);
  assert(commands.size() == lines.points.size());
  ProgramCompensation r;
  fillCompensatedPoints(r, lines.points, commands);
  const detail::RewriteInput input{
      scan.offset_lines, moves.frames, lines, cycle_events, axes, scan.comp_lines};
  detail::writeCompensatedText(text, input, r);
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
