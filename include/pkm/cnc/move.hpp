/// @file
/// @brief One motion of an interpreted G-code program in machine coordinates, the sink interface
/// that receives motions as they are produced, and the `pkm gcode moves` CSV row format
/// (docs/gcode.md).
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "pkm/cnc/comment_message.hpp"

namespace pkm::cnc {

/// Kind of motion: G0 rapid, G1 (and canned-cycle feeds) linear feed, G2/G3 arc.
enum class MoveKind { kRapid, kLinear, kArc };

/// Active plane of G17/G18/G19 (the arc plane; its normal is Z, Y, X respectively).
enum class Plane { kXY, kXZ, kYZ };

/// "rapid", "linear" or "arc".
[[nodiscard]] const char* toString(MoveKind kind);
/// "XY", "XZ" or "YZ".
[[nodiscard]] const char* toString(Plane plane);
/// Indices into (X, Y, Z) of a plane's first axis, second axis and normal, in LinuxCNC's
/// orientation (the G2/G3 sense and canned-cycle axes follow it): G17 (X, Y, Z), G18 (Z, X, Y),
/// G19 (Y, Z, X).
[[nodiscard]] std::array<std::size_t, 3> planeAxes(Plane plane);

/// One motion, everything in machine coordinates: G5x, G92 and tool length offsets applied,
/// lengths in mm and angles in degrees whatever G20/G21 said (LinuxCNC's machine position).
struct Move {
  std::size_t line = 0;              ///< 1-based source line of the block that caused it
  MoveKind kind = MoveKind::kRapid;  ///< rapid, linear feed or arc
  std::array<double, 6> end{};       ///< end point X, Y, Z (mm), A, B, C (deg)
  /// Arc centre X, Y, Z (mm) for arcs; the coordinate along the plane normal is NaN (a helix has
  /// no single centre height); all NaN for lines.
  std::array<double, 3> centre{std::numeric_limits<double>::quiet_NaN(),
                               std::numeric_limits<double>::quiet_NaN(),
                               std::numeric_limits<double>::quiet_NaN()};
  /// Signed number of turns of an arc: G2 (clockwise seen from the plane normal) negative, G3
  /// positive, |turns| = P (default 1); 0 for lines. LinuxCNC's ARC_FEED "rotation".
  int turns = 0;
  Plane plane = Plane::kXY;  ///< plane active when the move was made
  /// Feed rate in mm/min; NaN for rapids. In inverse-time mode (G93) the equivalent rate
  /// (path length x F), see docs/gcode.md.
  double feed = std::numeric_limits<double>::quiet_NaN();
};

struct Block;

/// What a canned cycle does besides moving and dwelling, in order with its motions
/// (MoveSink::onCycleAction): spindle stop (M5), start clockwise (M3) or counter-clockwise (M4),
/// orientation (M19), feed and speed overrides off (M49) and on again (M48) around a tap, and
/// G88's program stop (M0) for a manual retraction.
enum class CycleAction {
  kSpindleStop,
  kSpindleClockwise,
  kSpindleCounterClockwise,
  kSpindleOrient,
  kOverridesOff,
  kOverridesOn,
  kProgramStop
};

/// A word of an executed block with the value its expression had when the block ran.
struct EvaluatedWord {
  char letter = 0;  ///< lower case, as in Block::words
  double value = 0.0;
};

/// Receives motions in program order (a later `gcode run` streams them instead of collecting).
class MoveSink {
 public:
  virtual ~MoveSink() = default;
  /// True when the sink wants onBlock calls (asked once per run; evaluating them costs time).
  [[nodiscard]] virtual bool wantsBlocks() const { return false; }
  /// Called for every block the interpreter reaches, in execution order (loop bodies once per
  /// pass), before the block's motions: `index` is its position in Program::blocks(); `words`
  /// holds the evaluated words of an ordinary block in source order (empty for an O-word
  /// statement, which reaches it unevaluated). Blocks skipped by block delete are not reported.
  virtual void onBlock(const Block& block,
                       std::size_t index,
                       const std::vector<EvaluatedWord>& words) {
    (void)block;
    (void)index;
    (void)words;
  }
  /// Called once per motion, in execution order.
  virtual void onMove(const Move& move) = 0;
  /// Called once per dwell, in execution order with the motions: a G4 block and the dwell at the
  /// bottom of a G82/G89 cycle. `seconds` ≥ 0. The default ignores it.
  virtual void onDwell(std::size_t line, double seconds) {
    (void)line;
    (void)seconds;
  }
  /// Called for each non-motion action of a canned cycle (G74/G84/G86/G87/G88), in execution
  /// order with the motions and dwells. The default ignores it.
  virtual void onCycleAction(std::size_t line, CycleAction action) {
    (void)line;
    (void)action;
  }
  /// Called when the tool in the spindle changes (M6, M61), in order with the motions and before
  /// the motions of the block that changed it, and once, at the first block that does anything,
  /// with the tool the run starts with: `tool` is its number (0: none). The default ignores it.
  virtual void onToolChange(std::size_t line, int tool) {
    (void)line;
    (void)tool;
  }
  /// Called for each active comment a block runs (MSG, DEBUG, PRINT, LOG...; ABORT is an error
  /// instead), in order with the motions and before the block's own motions; `text` has its
  /// parameters substituted (but MSG's). The default ignores it.
  virtual void onMessage(std::size_t line, CommentKind kind, const std::string& text) {
    (void)line;
    (void)kind;
    (void)text;
  }
};

/// An active comment of a program as a sink received it.
struct MessageEvent {
  std::size_t line = 0;  ///< 1-based source line
  CommentKind kind = CommentKind::kNone;
  std::string text;  ///< after parameter substitution
};

/// A dwell of a program: `seconds` (≥ 0) after the first `after_moves` motions.
struct DwellEvent {
  std::size_t line = 0;         ///< 1-based source line (the G4 block or the cycle)
  std::size_t after_moves = 0;  ///< motions made before it
  double seconds = 0.0;
};

/// A change of the tool in the spindle: `tool` (0: none) from the motion `after_moves` (0-based)
/// on.
struct ToolChangeEvent {
  std::size_t line = 0;         ///< 1-based source line (M6, M61; the first block for the start)
  std::size_t after_moves = 0;  ///< motions made before it
  int tool = 0;
};

/// A sink that keeps every motion and dwell in a vector.
class MoveCollector final : public MoveSink {
 public:
  void onMove(const Move& move) override { moves.push_back(move); }
  void onDwell(std::size_t line, double seconds) override {
    dwells.push_back({line, moves.size(), seconds});
  }
  void onMessage(std::size_t line, CommentKind kind, const std::string& text) override {
    messages.push_back({line, kind, text});
  }
  void onToolChange(std::size_t line, int tool) override {
    tool_changes.push_back({line, moves.size(), tool});
  }
  std::vector<Move> moves;                    ///< the motions received, in order
  std::vector<DwellEvent> dwells;             ///< the dwells received, in order
  std::vector<MessageEvent> messages;         ///< the active comments received, in order
  std::vector<ToolChangeEvent> tool_changes;  ///< the tools in the spindle, in order
};

/// Header of the moves CSV: `line,kind,x,y,z,a,b,c,cx,cy,cz,turns,plane,feed`.
inline constexpr const char* kMoveCsvHeader = "line,kind,x,y,z,a,b,c,cx,cy,cz,turns,plane,feed";

/// The most characters one CSV row of writeMoveCsv can take (newline included).
inline constexpr std::size_t kMaxMoveCsvRow = 512;

/// Writes one CSV row (with the newline) for `move` at `out`, which must have room for
/// kMaxMoveCsvRow characters, and returns the end: numbers in shortest round-trip form, NaN
/// fields (unused centre coordinates, the feed of a rapid) left empty.
char* writeMoveCsv(char* out, const Move& move);

/// Appends the row of writeMoveCsv to `out`.
void appendMoveCsv(std::string& out, const Move& move);

}  // namespace pkm::cnc
