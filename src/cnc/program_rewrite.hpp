// Private to the cnc module: the text side of `gcode compensate` (program_compensation.cpp reads
// and interpolates the program, program_rewrite.cpp writes it): the number format of the
// rewritten axis words, the rewriting of one source line, and the line-by-line output.
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "pkm/cnc/expression.hpp"
#include "pkm/cnc/program_compensation.hpp"

namespace pkm::cnc::detail {

/// The parameters of a constant expression: none exists, each reads 0.
struct NoParams final : ParameterSource {
  double numbered(int) override { return 0.0; }
  double named(const std::string&) override { return 0.0; }
  bool exists(const std::string&) override { return false; }
};

/// Appends letter and `nano` / 1e9 with up to 9 decimals, trailing zeros dropped (from the
/// integer, so incremental words add up exactly to the absolute values they stand for).
void appendCoord(std::string& out, char letter, long long nano);

/// What the axis words of a motion's line mean: program = (machine − offset) / scale (scale 25.4
/// for the lengths under G20, 1 for angles), absolute or relative to the previous position.
struct WordFrame {
  Axes offset{};
  double scale = 1.0;
  bool incremental = false;
  bool machine = false;  ///< G53 (non-modal: repeated on the inserted segment lines)
};

/// The six axis words that command machine position `c` from `previous` (the last commanded
/// machine position) under `f`.
std::string axisWords(const Axes& c,
                      const Axes& previous,
                      const WordFrame& f,
                      const AxisMask& axes);

/// What rewriteLine replaces: a line's motion (G0..G3 and X..C, I J K R, P of an arc; the new
/// words go after the N word), a drilling cycle (also its G word and R, Q, P, L), or the axis
/// words of a G92/G10 L20 line (X..C only; the new words go where the first of them was).
enum class Rewrite { kMotion, kArc, kCycle, kOffset, kCutterComp };

/// The line with the words `what` names removed and `words` inserted; comments, blanks and
/// other words stay where they are.
std::string rewriteLine(std::string_view line, Rewrite what, const std::string& words);

/// A G92 or G10 L20 line: it sets an offset so that the *current* position reads as the given
/// values. On the pre-distorted machine the current position is the last command, not the
/// desired point, so each value is shifted by (command − desired)/scale to give the same offset.
struct OffsetLine {
  std::array<std::optional<double>, 6> values{};  ///< X Y Z A B C as written (program units)
  double scale = 1.0;                             ///< mm per program length unit on that line
};

/// A block inserted after a motion of an expanded cycle: a dwell or a cycle action.
struct CycleEvent {
  std::size_t line = 0;         ///< source line (the cycle's)
  std::size_t after_moves = 0;  ///< motions made before it
  std::string text;             ///< the block
};

/// The interpolated points of each line's motions: one motion, or the consecutive motions of a
/// drilling cycle.
struct LineSpans {
  std::map<std::size_t, std::pair<std::size_t, std::size_t>> span;  ///< line -> [first, last)
  std::map<std::size_t, std::size_t> motions_of_line;               ///< line -> motions
  std::vector<PathPoint> points;                                    ///< all, in order
};

/// What writeCompensatedText reads besides the compensated points.
struct RewriteInput {
  const std::map<std::size_t, OffsetLine>& offset_lines;  ///< G92 / G10 L20 lines by line
  const std::vector<WordFrame>& frames;                   ///< word frame of each motion
  LineSpans& lines;                                       ///< the interpolated points by line
  std::map<std::size_t, std::vector<CycleEvent>>& cycle_events;  ///< of multi-motion lines
  const AxisMask& axes;                                          ///< the axis words written
  /// Lines whose G41/G42/G41.1/G42.1 and D words are removed: the written motions are the
  /// compensated tool path already, which the controller must not offset again.
  const std::set<std::size_t>& comp_lines;
};

/// Appends program `text` rewritten line by line (line numbers 1-based as in Program) to
/// r.text; r.points holds the compensated points. Counts the motion, added and offset lines.
void writeCompensatedText(std::string_view text, const RewriteInput& in, ProgramCompensation& r);

}  // namespace pkm::cnc::detail
