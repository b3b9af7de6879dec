// Line reader after the LinuxCNC 2.9 G-code overview, "Format of a line", "Comments", "O Codes":
// blanks and case are dropped outside comments, comments are removed, then the line is read as
// [/] [N number] { word | parameter setting } or as one O-word statement.
#include <fmt/format.h>

#include <array>
#include <cstdint>
#include <string>

#include "pkm/cnc/block.hpp"
#include "pkm/cnc/gcode_error.hpp"
#include "plain_number.hpp"

namespace pkm::cnc {

namespace {

constexpr std::size_t kMaxLineLength = 256;  // LinuxCNC LINELEN

bool isAlpha(char c) { return c >= 'a' && c <= 'z'; }
bool isDigit(char c) { return c >= '0' && c <= '9'; }

/// What normalize does with a character: keep it, lower-case it, drop it (blanks), or look
/// closer (comments, ';', ')', characters outside printable ASCII).
enum class CharClass : std::uint8_t { kKeep, kUpper, kBlank, kSpecial };

constexpr std::array<CharClass, 256> kCharClass = [] {
  std::array<CharClass, 256> t{};
  for (std::size_t c = 0; c < 256; ++c) {
    if (c < 32 || c > 126 || c == '(' || c == ')' || c == ';')
      t[c] = CharClass::kSpecial;
    else if (c >= 'A' && c <= 'Z')
      t[c] = CharClass::kUpper;
    else
      t[c] = CharClass::kKeep;
  }
  t[' '] = t['\t'] = t['\r'] = CharClass::kBlank;
  return t;
}();

/// Lower-cases and removes blanks and comments; writes the result to `out` (room for
/// text.size() characters) and returns it. The last parenthesised comment's kind and text go to
/// `block` (classifyComment).
std::string_view normalize(std::string_view text, char* out, Block& block) {
  char* o = out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    switch (kCharClass[static_cast<unsigned char>(c)]) {
      case CharClass::kKeep:
        *o++ = c;
        continue;
      case CharClass::kUpper:
        *o++ = static_cast<char>(c - 'A' + 'a');
        continue;
      case CharClass::kBlank:
        continue;
      case CharClass::kSpecial:
        break;
    }
    if (c == '(') {
      const std::size_t close = text.find(')', i + 1);
      if (close == std::string_view::npos) throw GcodeError("comment not closed: missing ')'");
      const std::size_t nested = text.find('(', i + 1);
      if (nested < close) throw GcodeError("nested comment: '(' inside a comment");
      block.comment = classifyComment(text.substr(i + 1, close - i - 1), block.comment_text);
      i = close;
      continue;
    }
    if (c == ';') {
      std::string ignored;
      (void)classifyComment(text.substr(i + 1), ignored);  // refuses ";py," lines
      break;
    }
    if (c == ')') throw GcodeError("')' without '('");
    throw GcodeError(fmt::format("bad character (code {}) in line", static_cast<unsigned char>(c)));
  }
  return {out, static_cast<std::size_t>(o - out)};
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
  if (pos < s.size() && s[pos] == '[') {
    block.o_label = Expression::parseBracketed(s, pos);
  } else if (pos < s.size() && s[pos] == '#') {  // o#<name> call: the number a parameter holds
    block.o_label = Expression::parseReal(s, pos);
  } else if (pos < s.size() && s[pos] == '<') {
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
  if (block.o_name.empty() && !block.o_label) throw GcodeError("O-word without a number or name");
  const std::size_t kstart = pos;
  while (pos < s.size() && isAlpha(s[pos])) ++pos;
  if (pos == kstart && pos == s.size() && !block.o_label) {
    block.o_kind = OKind::kProgram;  // a program label: main program title or M98 subprogram
    return;
  }
  if (pos == kstart) throw GcodeError("O-word without a keyword (sub, call, if, while, ...)");
  block.o_kind = keyword(s.substr(kstart, pos - kstart));
  if (block.o_label && block.o_kind != OKind::kCall)
    throw GcodeError("O[expression] is only for calls: O[...] call");
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

bool isBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

/// Parses the common line "[N digits] word word ..." without normalizing it first: words are a
/// letter (either case) directly followed by a plain number (detail::scanPlainNumber), with
/// blanks only between words. Returns false, leaving `block` to be cleared, on anything else
/// (comments, '/', '%', O-words, parameters, expressions, a blank inside a number, an unknown or
/// repeated letter, ...): the general path then reads the line and reports any error, so both
/// paths give the same block for every line this one accepts.
bool parseSimpleLine(std::string_view text, Block& block) {
  const char* p = text.data();
  const char* const end = p + text.size();
  block.words.reserve(6);
  while (p < end && isBlank(*p)) ++p;
  if (p < end && (*p == 'n' || *p == 'N')) {
    const char* const start = ++p;
    while (p < end && isDigit(*p)) ++p;
    if (p == start || (p < end && !isBlank(*p) && !isAlpha(static_cast<char>(*p | 0x20))))
      return false;
  }
  std::uint32_t seen = 0;  // letters other than g and m already read, bit (letter - 'a')
  while (true) {
    while (p < end && isBlank(*p)) ++p;
    if (p == end) return true;
    const char c = static_cast<char>(*p | 0x20);  // lower case for letters
    if (!isAlpha(c) || c == 'n' || c == 'o' || c == 'e') return false;
    const std::uint32_t bit = std::uint32_t{1} << (c - 'a');
    if (c != 'g' && c != 'm') {
      if ((seen & bit) != 0) return false;
      seen |= bit;
    }
    ++p;
    double v = 0.0;
    if (p == end) return false;
    const char* const after = detail::scanPlainNumber(p, end, v);
    if (after == nullptr) return false;
    p = after;
    if (p < end && !isBlank(*p) && !isAlpha(static_cast<char>(*p | 0x20))) return false;
    block.words.push_back(Word{c, Expression(v)});
  }
}

}  // namespace

char writtenLetter(char letter) {
  if (letter == kPolarRadius) return '@';
  if (letter == kPolarAngle) return '^';
  return static_cast<char>(std::toupper(static_cast<unsigned char>(letter)));
}

std::string oLabel(const std::string& name) {
  const bool numeric = !name.empty() && name.find_first_not_of("0123456789") == std::string::npos;
  return numeric ? "o" + name : "o<" + name + ">";
}

void Block::clear() {
  block_delete = false;
  words.clear();
  assignments.clear();
  o_kind = OKind::kNone;
  o_name.clear();
  o_args.clear();
  o_label.reset();
  jump = kNoBlock;
  partner = kNoBlock;
  closes_do = false;
  comment = CommentKind::kNone;
  comment_text.clear();
  deferred_error.clear();
}

LineMark parseLine(std::string_view text, Block& block) {
  block.clear();  // `line` is left to the caller
  if (text.size() > kMaxLineLength)
    throw GcodeError(fmt::format("line longer than {} characters", kMaxLineLength));
  if (parseSimpleLine(text, block)) return LineMark::kNormal;
  block.clear();
  std::array<char, kMaxLineLength> buffer;
  const std::string_view s = normalize(text, buffer.data(), block);
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
  std::array<bool, 28> seen{};  // a..z, @, ^
  block.words.reserve(6);
  while (pos < s.size()) {
    const char c = s[pos];
    if (c == '#') {
      Assignment a;
      ++pos;
      if (pos < s.size() && s[pos] == '<') {
        const std::size_t close = s.find('>', pos);
        if (close == std::string_view::npos) throw GcodeError("named parameter not terminated");
        a.named = true;
        a.name = std::string(s.substr(pos + 1, close - pos - 1));
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
    if (!isAlpha(c) && c != '@' && c != '^')
      throw GcodeError(fmt::format("bad character '{}' where a word was expected", c));
    if (c == 'n') throw GcodeError("N word not at the start of the line");
    if (c == 'o') throw GcodeError("O-word not at the start of the line");

    const char letter = c == '@' ? kPolarRadius : c == '^' ? kPolarAngle : c;
    const auto idx = static_cast<std::size_t>(letter - 'a');
    if (c != 'g' && c != 'm') {
      if (seen[idx]) throw GcodeError(fmt::format("multiple {} words on one line", c));
      seen[idx] = true;
    }
    ++pos;
    Word w;
    w.letter = letter;
    w.value = Expression::parseReal(s, pos);
    block.words.push_back(std::move(w));
  }
  return LineMark::kNormal;
}

}  // namespace pkm::cnc
