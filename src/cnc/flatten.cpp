// Flattening: an interpreter run reports every block it reaches (MoveSink::onBlock); ordinary
// blocks are written back with their evaluated words, O-word statements are dropped, and the
// comment lines the source runs straight through are copied.
#include "pkm/cnc/flatten.hpp"

#include <fmt/format.h>

#include <cassert>
#include <cctype>
#include <cmath>

#include "pkm/cnc/program.hpp"
#include "pkm/core/error.hpp"

namespace pkm::cnc {

std::string formatGcodeNumber(double value) {
  assert(std::isfinite(value));
  if (value == 0.0) return "0";
  std::string s = fmt::format("{}", value);
  if (s.find_first_of("eE") == std::string::npos) return s;
  // Exponent form: print fixed with as many decimals as the shortest form needs.
  const std::size_t e = s.find_first_of("eE");
  const int exponent = std::stoi(s.substr(e + 1));
  const std::size_t mantissa_digits =
      s.substr(0, e).find('.') == std::string::npos ? 0 : e - s.substr(0, e).find('.') - 1;
  const int decimals = std::max(0, static_cast<int>(mantissa_digits) - exponent);
  std::string f = fmt::format("{:.{}f}", value, decimals);
  if (f.find('.') != std::string::npos) {
    while (f.back() == '0') f.pop_back();
    if (f.back() == '.') f.pop_back();
  }
  return f;
}

namespace {

/// The comments of a source line, `( )` and `;`, separated by single blanks.
std::string commentsOf(std::string_view line) {
  std::string out;
  for (std::size_t i = 0; i < line.size(); ++i) {
    if (line[i] == ';') {
      if (!out.empty()) out.push_back(' ');
      out.append(line.substr(i));
      break;
    }
    if (line[i] != '(') continue;
    const std::size_t close = line.find(')', i);
    const std::size_t end = close == std::string_view::npos ? line.size() : close + 1;
    if (!out.empty()) out.push_back(' ');
    out.append(line.substr(i, end - i));
    i = end - 1;
  }
  while (!out.empty() && (out.back() == '\r' || out.back() == ' ')) out.pop_back();
  return out;
}

bool isPercentLine(std::string_view line) {
  std::size_t i = 0;
  while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
  if (i == line.size() || line[i] != '%') return false;
  for (++i; i < line.size(); ++i)
    if (!std::isspace(static_cast<unsigned char>(line[i]))) return false;
  return true;
}

class FlattenSink final : public MoveSink {
 public:
  /// What the M98/M99 of a block's words do (the passes of the M98 calls still running are
  /// counted, so that the M99 of the main program is told from a subprogram's).
  struct Fanuc {
    bool m98 = false;
    bool ends_main = false;
  };
  FlattenSink(const Program& program, const std::vector<std::string_view>& lines, FlatProgram& out)
      : program_(program), lines_(lines), out_(out) {}

  [[nodiscard]] bool wantsBlocks() const override { return true; }
  void onMove(const Move&) override {}

  void onBlock(const Block& block,
               std::size_t index,
               const std::vector<EvaluatedWord>& words) override {
    const std::vector<Block>& blocks = program_.blocks();
    if (index != kNoBlock && (index == 0 ? !reported_ : straightOn(index)))
      copyLines(index == 0 ? 1 : blocks[index - 1].line + 1, block.line);
    reported_ = true;
    last_ = index;
    if (block.o_kind == OKind::kCall) ++sub_depth_;
    if (block.o_kind == OKind::kEndSub || block.o_kind == OKind::kReturn) --sub_depth_;
    if (block.o_kind != OKind::kNone) return;
    refuseModalState(block, words);
    // A sub file's block (no index in the program) keeps no comment: its lines are not ours.
    const std::string_view src =
        index != kNoBlock && block.line <= lines_.size() ? lines_[block.line - 1] : "";
    const std::string comments = commentsOf(src);
    if (words.empty() && comments.empty()) return;  // a line of parameter settings only
    const Fanuc fanuc = fanucOf(words);
    std::string text = wordsText(block, words, fanuc, false);
    if (text.size() > kMaxLine) text = wordsText(block, words, fanuc, true);
    if (text.size() > kMaxLine)
      throw IoError(fmt::format("{}:{}: the evaluated block is longer than {} characters",
                                program_.file(),
                                block.line,
                                kMaxLine));
    if (!comments.empty()) {
      // Comments go on a line of their own when the block would be too long with them.
      if (text.size() + 1 + comments.size() > kMaxLine) {
        emit(comments, block.line);
      } else {
        if (!text.empty() && text != "/") text.push_back(' ');
        text += comments;
      }
    }
    if (!text.empty()) emit(text, block.line);
    ++out_.blocks;
  }

  /// After the run: the lines after the last block when the run reached it, and a closing `%`.
  void finish() {
    const std::vector<Block>& blocks = program_.blocks();
    if (blocks.empty())
      copyLines(1, program_.lineCount() + 1);
    else if (reported_ && last_ + 1 == blocks.size())
      copyLines(blocks.back().line + 1, program_.lineCount() + 1);
    if (percent_lines_ % 2 == 1) emit("%", program_.lineCount());
  }

 private:
  /// True when the run reaches block `index` > 0 through the source lines just before it: from
  /// block index − 1, or into the body of the sub, branch or loop that block opens (a call, a
  /// loop's next pass and a taken branch jump there).
  [[nodiscard]] bool straightOn(std::size_t index) const {
    if (!reported_) return false;
    if (last_ + 1 == index) return true;
    const Block& before = program_.blocks()[index - 1];
    switch (before.o_kind) {
      case OKind::kSub:
      case OKind::kIf:
      case OKind::kElseIf:
      case OKind::kElse:
      case OKind::kDo:
      case OKind::kRepeat:
        return true;
      case OKind::kWhile:
        return !before.closes_do;
      default:
        return false;
    }
  }

  /// LinuxCNC's longest line (LINELEN).
  static constexpr std::size_t kMaxLine = 256;

  /// The block's words as a line: exact values, or (`rounded`, for a line that would be too
  /// long) values rounded to 9 decimals, as gcode compensate writes its words.
  std::string wordsText(const Block& block,
                        const std::vector<EvaluatedWord>& words,
                        const Fanuc& fanuc,
                        bool rounded) const {
    std::string text = block.block_delete ? "/" : "";
    for (const EvaluatedWord& w : words) {
      // The flat program holds the subprogram's blocks: M98 and its P, L go; an M99 goes, but
      // the one that ends the main program becomes M2.
      if (fanuc.m98 && (w.letter == 'p' || w.letter == 'l')) continue;
      if (w.letter == 'm' && (w.value == 98.0 || w.value == 99.0)) {
        if (w.value == 98.0 || !fanuc.ends_main) continue;
      }
      if (!std::isfinite(w.value))
        throw IoError(fmt::format("{}:{}: {} word value is not a finite number",
                                  program_.file(),
                                  block.line,
                                  static_cast<char>(std::toupper(w.letter))));
      if (text.size() > (block.block_delete ? 1u : 0u)) text.push_back(' ');
      text.push_back(writtenLetter(w.letter));
      const bool round = rounded && std::abs(w.value) < 1e9;
      const double v = w.letter == 'm' && w.value == 99.0 ? 2.0 : w.value;
      text += formatGcodeNumber(round ? std::round(v * 1e9) / 1e9 : v);
    }
    return text;
  }

  [[nodiscard]] Fanuc fanucOf(const std::vector<EvaluatedWord>& words) {
    Fanuc f;
    double count = 1.0;
    bool m99 = false;
    for (const EvaluatedWord& w : words) {
      if (w.letter == 'm' && w.value == 98.0) f.m98 = true;
      if (w.letter == 'm' && w.value == 99.0) m99 = true;
      if (w.letter == 'l') count = w.value;
    }
    if (f.m98 && count >= 1.0) passes_.push_back(std::floor(count));
    if (m99) {
      if (passes_.empty()) {
        f.ends_main = true;
      } else if (--passes_.back() < 1.0) {
        passes_.pop_back();
      }
    }
    return f;
  }

  /// Throws for M73 anywhere, and for M70-M72 inside a subroutine: the saved state is per call
  /// level, and the flat program has one.
  void refuseModalState(const Block& block, const std::vector<EvaluatedWord>& words) const {
    for (const EvaluatedWord& w : words) {
      if (w.letter != 'm' || w.value < 70.0 || w.value > 73.0) continue;
      if (w.value == 73.0 || sub_depth_ > 0 || !passes_.empty())
        throw IoError(
            fmt::format("{}:{}: gcode flatten does not support M73, nor M70-M72 in a "
                        "subroutine: their saved state belongs to a call level and the "
                        "flat program has one",
                        program_.file(),
                        block.line));
    }
  }

  /// Copies source lines [from, to) (1-based): they hold no block, only comments or blanks.
  void copyLines(std::size_t from, std::size_t to) {
    for (std::size_t l = from; l < to && l <= lines_.size(); ++l) {
      std::string_view s = lines_[l - 1];
      if (!s.empty() && s.back() == '\r') s.remove_suffix(1);
      if (isPercentLine(s)) ++percent_lines_;
      emit(std::string(s), l);
    }
  }

  void emit(const std::string& text, std::size_t source_line) {
    out_.text += text;
    out_.text.push_back('\n');
    out_.source_line.push_back(source_line);
  }

  const Program& program_;
  const std::vector<std::string_view>& lines_;
  FlatProgram& out_;
  bool reported_ = false;
  std::vector<double> passes_;  // passes left of the M98 calls running, innermost last
  int sub_depth_ = 0;           // O-word subs being run
  std::size_t last_ = 0;
  int percent_lines_ = 0;
};

}  // namespace

FlatProgram flattenProgram(std::string_view text,
                           const std::string& file,
                           const InterpreterOptions& options) {
  const Program program = Program::parse(text, file);
  std::vector<std::string_view> lines;
  for (std::size_t start = 0; start < text.size();) {
    std::size_t nl = text.find('\n', start);
    if (nl == std::string_view::npos) nl = text.size();
    lines.push_back(text.substr(start, nl - start));
    start = nl + 1;
  }
  FlatProgram out;
  for (const Block& b : program.blocks())
    if (b.o_kind != OKind::kNone) out.had_o_words = true;
  FlattenSink sink(program, lines, out);
  Interpreter interpreter(options);
  (void)interpreter.run(program, sink);
  sink.finish();
  return out;
}

}  // namespace pkm::cnc
