// Line reader after the LinuxCNC 2.9 G-code overview, "Format of a line", "Comments", "O Codes":
// blanks and case are dropped outside comments, comments are removed, then the line is read as
// [/] [N number] { word | parameter setting } or as one O-word statement.
#include <fmt/format.h>

#include <array>
#include <string>

#include "pkm/cnc/block.hpp"
#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {

namespace {

constexpr std::size_t kMaxLineLength = 256;  // LinuxCNC LINELEN

bool isAlpha(char c) { return c >= 'a' && c <= 'z'; }
bool isDigit(char c) { return c >= '0' && c <= '9'; }

/// Lower-cases and removes blanks and comments. Returns false when the line is only '%'.
void normalize(std::string_view text, std::string& out) {
  out.clear();
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '(') {
      const std::size_t close = text.find(')', i + 1);
      if (close == std::string_view::npos) throw GcodeError("comment not closed: missing ')'");
      const std::size_t nested = text.find('(', i + 1);
      if (nested < close) throw GcodeError("nested comment: '(' inside a comment");
      i = close;
      continue;
    }
    if (c == ';') break;
    if (c == ' ' || c == '\t' || c == '\r') continue;
    if (c == ')') throw GcodeError("')' without '('");
    const auto u = static_cast<unsigned char>(c);
    if (u < 32 || u > 126) throw GcodeError(fmt::format("bad character (code {}) in line", u));
    out.push_back(c >= 'A' && c <= 'Z' ? static_cast<char>(c - 'A' + 'a') : c);
  }
}

OKind keyword(std::string_view k) {
  static constexpr std::array<std::pair<std::string_view, OKind>, 15> kKeys{{
      {"sub", OKind::kSub},
      {"endsub", OKind::kEndSub},
      {"call", OKind::kCall},
      {"return", OKind::kReturn},
      {"if", OKind::kIf},
      {"elseif", OKind::kElseIf},
      {"else", OKind::kElse},
      {"endif", OKind::kEndIf},
      {"while", OKind::kWhile},
      {"endwhile", OKind::kEndWhile},
      {"do", OKind::kDo},
      {"repeat", OKind::kRepeat},
      {"endrepeat", OKind::kEndRepeat},
      {"break", OKind::kBreak},
      {"continue", OKind::kContinue},
  }};
  for (const auto& [name, kind] : kKeys)
    if (name == k) return kind;
  throw GcodeError(fmt::format("unknown O-word keyword '{}'", k));
}

void parseOWord(std::string_view s, std::size_t pos, Block& block) {
  ++pos;  // 'o'
  if (pos < s.size() && s[pos] == '<') {
    const std::size_t close = s.find('>', pos);
    if (close == std::string_view::npos)
      throw GcodeError("O-word name not terminated: missing '>'");
    block.o_name = std::string(s.substr(pos + 1, close - pos - 1));
    pos = close + 1;
  } else {
    const std::size_t start = pos;
    while (pos < s.size() && isDigit(s[pos])) ++pos;
    block.o_name = std::string(s.substr(start, pos - start));
  }
  if (block.o_name.empty()) throw GcodeError("O-word without a number or name");
  const std::size_t kstart = pos;
  while (pos < s.size() && isAlpha(s[pos])) ++pos;
  if (pos == kstart) throw GcodeError("O-word without a keyword (sub, call, if, while, ...)");
  block.o_kind = keyword(s.substr(kstart, pos - kstart));
  while (pos < s.size() && s[pos] == '[')
    block.o_args.push_back(Expression::parseBracketed(s, pos));
  if (pos != s.size())
    throw GcodeError(fmt::format("unexpected '{}' after O-word statement", s.substr(pos)));
  const std::size_t n = block.o_args.size();
  switch (block.o_kind) {
    case OKind::kIf:
    case OKind::kElseIf:
    case OKind::kWhile:
    case OKind::kRepeat:
      if (n != 1)
        throw GcodeError(
            fmt::format("{} needs exactly one [condition or count]", oLabel(block.o_name)));
      break;
    case OKind::kReturn:
    case OKind::kEndSub:
      if (n > 1) throw GcodeError("return/endsub take at most one [value]");
      break;
    case OKind::kCall:
      if (n > 30) throw GcodeError("a call takes at most 30 arguments");
      break;
    default:
      if (n != 0) throw GcodeError("this O-word statement takes no value");
  }
}

}  // namespace

std::string oLabel(const std::string& name) {
  const bool numeric = !name.empty() && name.find_first_not_of("0123456789") == std::string::npos;
  return numeric ? "o" + name : "o<" + name + ">";
}

LineMark parseLine(std::string_view text, Block& block) {
  const std::size_t line = block.line;
  block = Block{};
  block.line = line;
  if (text.size() > kMaxLineLength)
    throw GcodeError(fmt::format("line longer than {} characters", kMaxLineLength));
  thread_local std::string s;
  normalize(text, s);
  if (s == "%") return LineMark::kPercent;
  std::size_t pos = 0;
  if (pos < s.size() && s[pos] == '/') {
    block.block_delete = true;
    ++pos;
  }
  if (pos < s.size() && s[pos] == 'n') {
    ++pos;
    const std::size_t start = pos;
    while (pos < s.size() && (isDigit(s[pos]) || s[pos] == '.')) ++pos;
    if (pos == start) throw GcodeError("N without a line number");
  }
  if (pos < s.size() && s[pos] == 'o') {
    parseOWord(s, pos, block);
    return LineMark::kNormal;
  }
  std::array<bool, 26> seen{};
  block.words.reserve(6);
  while (pos < s.size()) {
    const char c = s[pos];
    if (c == '#') {
      Assignment a;
      ++pos;
      if (pos < s.size() && s[pos] == '<') {
        const std::size_t close = s.find('>', pos);
        if (close == std::string::npos) throw GcodeError("named parameter not terminated");
        a.named = true;
        a.name = s.substr(pos + 1, close - pos - 1);
        if (a.name.empty()) throw GcodeError("empty parameter name");
        pos = close + 1;
      } else {
        a.index = Expression::parseReal(s, pos);
      }
      if (pos >= s.size() || s[pos] != '=') throw GcodeError("'=' missing in parameter setting");
      ++pos;
      a.value = Expression::parseReal(s, pos);
      block.assignments.push_back(std::move(a));
      continue;
    }
    if (c == '@' || c == '^') throw GcodeError("polar coordinates (@, ^) are not supported");
    if (!isAlpha(c))
      throw GcodeError(fmt::format("bad character '{}' where a word was expected", c));
    if (c == 'n') throw GcodeError("N word not at the start of the line");
    if (c == 'o') throw GcodeError("O-word not at the start of the line");
    if (c == 'e' || c == 'o') throw GcodeError(fmt::format("unknown word letter '{}'", c));
    const auto idx = static_cast<std::size_t>(c - 'a');
    if (c != 'g' && c != 'm') {
      if (seen[idx]) throw GcodeError(fmt::format("multiple {} words on one line", c));
      seen[idx] = true;
    }
    ++pos;
    Word w;
    w.letter = c;
    w.value = Expression::parseReal(s, pos);
    block.words.push_back(std::move(w));
  }
  return LineMark::kNormal;
}

}  // namespace pkm::cnc
