#include "pkm/cnc/program_compensation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <cctype>
#include <cmath>
#include <map>

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

/// G words (×10) the rewrite cannot express in absolute machine coordinates.
bool unsupportedG(long g10) {
  static constexpr long kBad[] = {200, 910, 911, 920, 921, 922, 923, 100, 430, 431,
                                  280, 281, 300, 301, 530, 730, 810, 820, 830, 850,
                                  890, 930, 382, 383, 384, 385, 330, 331, 760};
  return std::find(std::begin(kBad), std::end(kBad), g10) != std::end(kBad);
}

/// Rejects blocks outside the supported subset (see the header).
void checkBlock(const Block& b, const std::string& file) {
  if (b.o_kind != OKind::kNone) fail(file, b.line, "gcode compensate does not support O-words");
  for (const Word& w : b.words) {
    if (w.letter != 'g') continue;
    if (!w.value.isConstant()) fail(file, b.line, "gcode compensate needs constant G words");
    struct NoParams final : ParameterSource {
      double numbered(int) override { return 0.0; }
      double named(const std::string&) override { return 0.0; }
      bool exists(const std::string&) override { return false; }
    } params;
    const long g10 = std::lround(w.value.evaluate(params) * 10.0);
    if (unsupportedG(g10))
      fail(file,
           b.line,
           fmt::format("G{} is not supported by gcode compensate (the output is in absolute "
                       "machine coordinates: G21 G90, no offsets, no cycles)",
                       static_cast<double>(g10) / 10.0));
  }
}

/// Appends `v` with up to 9 decimals, trailing zeros dropped.
void appendCoord(std::string& out, char letter, double v) {
  std::string s = fmt::format("{:.9f}", v);
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  out.push_back(letter);
  out += s;
}

std::string axisWords(const Axes& c) {
  std::string s;
  static constexpr char kLetters[] = {'X', 'Y', 'Z', 'A', 'B', 'C'};
  for (std::size_t k = 0; k < 6; ++k) {
    if (k > 0) s.push_back(' ');
    appendCoord(s, kLetters[k], c[k]);
  }
  return s;
}

/// The line with its motion words removed and `words` inserted after the N word; comments,
/// blanks and other words stay where they are.
std::string rewriteLine(std::string_view line, bool arc, const std::string& words) {
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
        std::string_view("xyzabcijkr").find(l) != std::string_view::npos || (arc && l == 'p');
    if (l == 'g') {
      std::size_t p = 1;
      const Expression e = Expression::parseReal(compact, p);
      if (e.isConstant()) {
        struct NoParams final : ParameterSource {
          double numbered(int) override { return 0.0; }
          double named(const std::string&) override { return 0.0; }
          bool exists(const std::string&) override { return false; }
        } params;
        const double g = e.evaluate(params);
        drop = g == 0.0 || g == 1.0 || g == 2.0 || g == 3.0;
      }
    }
    if (l == 'n') {
      out.append(line.substr(i, end - i));
      insert_at = out.size();
    } else if (!drop) {
      out.append(line.substr(i, end - i));
    }
    i = end;
    if (drop)  // the blanks after a removed word go with it
      while (i < n && (line[i] == ' ' || line[i] == '\t')) ++i;
  }
  // No trailing blanks that the source line did not have.
  const bool blank_end = !line.empty() && (line.back() == ' ' || line.back() == '\t');
  while (!blank_end && !out.empty() && (out.back() == ' ' || out.back() == '\t')) out.pop_back();
  if (insert_at == std::string::npos) {
    // After a block-delete slash and leading blanks.
    insert_at = 0;
    while (insert_at < out.size() &&
           (out[insert_at] == ' ' || out[insert_at] == '\t' || out[insert_at] == '/'))
      ++insert_at;
    out.insert(insert_at, words + " ");
  } else {
    out.insert(insert_at, " " + words);
  }
  return out;
}

}  // namespace

ProgramCompensation rewriteProgram(std::string_view text,
                                   const std::string& file,
                                   const PointMap& map,
                                   const InterpolationOptions& interpolation) {
  const Program program = Program::parse(text, file);
  for (const Block& b : program.blocks()) checkBlock(b, file);
  MoveCollector moves;
  Interpreter interpreter;
  (void)interpreter.run(program, moves);
  // Motions per line (one at most) and their interpolated points.
  std::map<std::size_t, std::pair<std::size_t, std::size_t>> span;  // line -> [first, last)
  std::vector<PathPoint> points;
  PathInterpolator interp(interpolation, moves.moves.empty() ? Axes{} : moves.moves.front().end);
  for (std::size_t m = 0; m < moves.moves.size(); ++m) {
    const Move& mv = moves.moves[m];
    if (span.count(mv.line) != 0) fail(file, mv.line, "gcode compensate needs one motion per line");
    const std::size_t first = points.size();
    interp.append(mv, static_cast<std::uint32_t>(m), points);
    span[mv.line] = {first, points.size()};
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
  std::size_t line_no = 0, start = 0;
  r.text.reserve(text.size() + text.size() / 2);
  while (start < text.size()) {
    ++line_no;
    std::size_t nl = text.find('\n', start);
    const bool has_nl = nl != std::string_view::npos;
    if (!has_nl) nl = text.size();
    std::string_view line = text.substr(start, nl - start);
    const auto it = span.find(line_no);
    if (it == span.end()) {
      r.text.append(line);
      if (has_nl) r.text.push_back('\n');
    } else {
      const auto [first, last] = it->second;
      const PathPoint& p0 = points[first];
      const bool cr = !line.empty() && line.back() == '\r';
      if (cr) line.remove_suffix(1);
      const std::string eol = cr ? "\r\n" : "\n";
      const char* g = p0.kind == MoveKind::kRapid ? "G0 " : "G1 ";
      r.text +=
          rewriteLine(line, p0.kind == MoveKind::kArc, g + axisWords(r.points[first].command));
      if (has_nl || last - first > 1) r.text += eol;
      ++r.motion_lines;
      for (std::size_t k = first + 1; k < last; ++k) {
        r.text += fmt::format("{}{} (pkm: line {} segment {}/{})",
                              g,
                              axisWords(r.points[k].command),
                              line_no,
                              k - first + 1,
                              last - first);
        if (has_nl || k + 1 < last) r.text += eol;
        ++r.added_lines;
      }
    }
    start = nl + 1;
  }
  return r;
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
  return rewriteProgram(text, file, map, options.interpolation);
}

ProgramCompensation compensateHybridProgram(std::string_view text,
                                            const std::string& file,
                                            const compensation::HybridSquarenessCompensation& c,
                                            double x2,
                                            bool base_frame_in_controller,
                                            const InterpolationOptions& interpolation) {
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
  return rewriteProgram(text, file, map, interpolation);
}

}  // namespace pkm::cnc
