// The text side of `gcode compensate`: see program_rewrite.hpp.
#include "program_rewrite.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <vector>

namespace pkm::cnc::detail {
namespace {

/// The codes (G number) that are expanded into G0/G1 lines, G4 dwells and M codes: the drilling,
/// tapping and boring cycles, and G28/G30 (the rapids to the intermediate point and to the stored
/// position).
bool cycleG(double g) {
  return g == 73.0 || g == 74.0 || g == 81.0 || g == 82.0 || g == 83.0 || g == 84.0 || g == 85.0 ||
         g == 86.0 || g == 89.0 || g == 28.0 || g == 30.0;
}

/// A value in program units, in nano-units (1e-9) as written.
long long nanoUnits(const Axes& machine, const WordFrame& f, std::size_t k) {
  const double v = (machine[k] - f.offset[k]) / (k < 3 ? f.scale : 1.0);
  return std::llround(v * 1e9);
}

/// A word or parameter setting of a source line, as rewriteLine reads it.
struct LineWord {
  std::size_t end = 0;  ///< one past its last character in the line
  char letter = 0;      ///< lower case; '#' for a parameter setting
  bool drop = false;    ///< removed by the rewrite
};

/// The word or parameter setting that starts at line[i] (a letter or '#'): its value spans
/// blanks up to the next word or comment. The compact text (no blanks, lower case) is parsed
/// with the interpreter's own reader.
LineWord readLineWord(std::string_view line, std::size_t i, Rewrite what) {
  const bool arc = what == Rewrite::kArc, offset = what == Rewrite::kOffset,
             cycle = what == Rewrite::kCycle, comp = what == Rewrite::kCutterComp;
  const std::size_t n = line.size();
  const char ch = line[i];
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
      comp ? l == 'd'
           : std::string_view(offset ? "xyzabc" : "xyzabcijkr").find(l) != std::string_view::npos ||
                 (arc && l == 'p') ||
                 (cycle && std::string_view("pql").find(l) != std::string_view::npos);
  if (l == 'g' && !offset) {
    std::size_t p = 1;
    const Expression e = Expression::parseReal(compact, p);
    if (e.isConstant()) {
      NoParams params;
      const double g = e.evaluate(params);
      drop = comp ? g == 41.0 || g == 42.0 || g == 41.1 || g == 42.1
                  : g == 0.0 || g == 1.0 || g == 2.0 || g == 3.0 || (cycle && cycleG(g));
    }
  }
  return {end, l, drop};
}

/// Puts `words` into the rewritten line `out`: on an offset line where the first removed word
/// was (`first_drop`), else after the N word (`insert_at`) or, without one, at the start after a
/// block-delete slash and leading blanks.
void insertWords(std::string& out,
                 Rewrite what,
                 const std::string& words,
                 std::size_t first_drop,
                 std::size_t insert_at) {
  if (what == Rewrite::kOffset && first_drop != std::string::npos) {
    if (first_drop < out.size()) {
      out.insert(first_drop, words + " ");
    } else {  // the axis words ended the line (its trailing blanks are gone)
      const bool blank = out.empty() || out.back() == ' ' || out.back() == '\t';
      out += blank ? words : " " + words;
    }
  } else if (what == Rewrite::kCutterComp) {
    // Nothing to insert: the removed words are said in a comment before any ';' comment.
    const std::size_t semi = out.find(';');
    const std::string note = "(pkm: cutter compensation is in the path)";
    if (semi == std::string::npos)
      out += out.empty() ? note : " " + note;
    else
      out.insert(semi, note + " ");
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
}

/// Appends G92/G10 L20 line `line_no` (`line` without its '\n') to r.text with its axis words
/// shifted by the correction at the current position: that of the last point before this line
/// (`next_point` advances past the points before it).
void appendOffsetLine(ProgramCompensation& r,
                      std::string_view line,
                      bool has_nl,
                      std::size_t line_no,
                      const OffsetLine& off,
                      std::size_t& next_point) {
  while (next_point < r.points.size() && r.points[next_point].line < line_no) ++next_point;
  Axes delta{};
  if (next_point > 0) {
    const CompensatedPoint& cp = r.points[next_point - 1];
    for (std::size_t k = 0; k < 6; ++k) delta[k] = cp.command[k] - cp.desired[k];
  }
  std::string words;
  static constexpr char kLetters[] = {'X', 'Y', 'Z', 'A', 'B', 'C'};
  for (std::size_t k = 0; k < 6; ++k) {
    const auto& v = off.values[k];
    if (!v) continue;
    if (!words.empty()) words.push_back(' ');
    const double shifted = *v + delta[k] / (k < 3 ? off.scale : 1.0);
    appendCoord(words, kLetters[k], std::llround(shifted * 1e9));
  }
  const bool cr = !line.empty() && line.back() == '\r';
  if (cr) line.remove_suffix(1);
  r.text += rewriteLine(line, Rewrite::kOffset, words);
  if (cr) r.text.push_back('\r');
  if (has_nl) r.text.push_back('\n');
  ++r.offset_lines;
}

/// Appends motion line `line_no` (`line` without its '\n') to r.text: its first point on the
/// line itself, the others and a cycle's dwells and actions on inserted lines.
void appendMotionLine(ProgramCompensation& r,
                      std::string_view line,
                      bool has_nl,
                      std::size_t line_no,
                      const std::pair<std::size_t, std::size_t>& span,
                      const RewriteInput& c) {
  const std::vector<PathPoint>& points = c.lines.points;
  const std::size_t first = span.first, last = span.second;
  const PathPoint& p0 = points[first];
  const bool cycle = c.lines.motions_of_line[line_no] > 1;
  // The previous commanded position: the interpreter's start-up position before the first.
  const auto previous = [&](std::size_t k) { return k == 0 ? Axes{} : r.points[k - 1].command; };
  const auto gWord = [&](std::size_t k) {
    return points[k].kind == MoveKind::kRapid ? "G0 " : "G1 ";
  };
  const auto words = [&](std::size_t k) {
    return axisWords(r.points[k].command, previous(k), c.frames[points[k].move], c.axes);
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
    for (const CycleEvent& d : c.cycle_events[line_no])
      if (d.after_moves == points[k].move + 1u) {
        inserted.push_back(d.text);
        ++r.added_lines;
      }
  };
  eventsAfter(first);
  for (std::size_t k = first + 1; k < last; ++k) {
    inserted.push_back(fmt::format("{}{}{} (pkm: line {} segment {}/{})",
                                   c.frames[points[k].move].machine ? "G53 " : "",
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

}  // namespace

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

std::string rewriteLine(std::string_view line, Rewrite what, const std::string& words) {
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
    const LineWord w = readLineWord(line, i, what);
    if (w.letter == 'n') {
      out.append(line.substr(i, w.end - i));
      insert_at = out.size();
    } else if (!w.drop) {
      out.append(line.substr(i, w.end - i));
    } else if (first_drop == std::string::npos) {
      first_drop = out.size();
    }
    i = w.end;
    if (w.drop)  // the blanks after a removed word go with it
      while (i < n && (line[i] == ' ' || line[i] == '\t')) ++i;
  }
  // No trailing blanks that the source line did not have.
  const bool blank_end = !line.empty() && (line.back() == ' ' || line.back() == '\t');
  while (!blank_end && !out.empty() && (out.back() == ' ' || out.back() == '\t')) out.pop_back();
  insertWords(out, what, words, first_drop, insert_at);
  return out;
}

void writeCompensatedText(std::string_view text, const RewriteInput& in, ProgramCompensation& r) {
  std::size_t line_no = 0, start = 0, next_point = 0;
  r.text.reserve(text.size() + text.size() / 2);
  while (start < text.size()) {
    ++line_no;
    std::size_t nl = text.find('\n', start);
    const bool has_nl = nl != std::string_view::npos;
    if (!has_nl) nl = text.size();
    std::string_view line = text.substr(start, nl - start);
    std::string stripped;
    if (in.comp_lines.count(line_no) != 0) {
      const bool cr = !line.empty() && line.back() == '\r';
      stripped = rewriteLine(cr ? line.substr(0, line.size() - 1) : line, Rewrite::kCutterComp, "");
      if (cr) stripped.push_back('\r');
      line = stripped;
    }
    const auto it = in.lines.span.find(line_no);
    const auto off = in.offset_lines.find(line_no);
    if (off != in.offset_lines.end()) {
      appendOffsetLine(r, line, has_nl, line_no, off->second, next_point);
    } else if (it == in.lines.span.end()) {
      r.text.append(line);
      if (has_nl) r.text.push_back('\n');
    } else {
      appendMotionLine(r, line, has_nl, line_no, it->second, in);
    }
    start = nl + 1;
  }
}

}  // namespace pkm::cnc::detail
