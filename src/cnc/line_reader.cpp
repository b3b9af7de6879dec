#include "pkm/cnc/line_reader.hpp"

#include <cstring>
#include <utility>

#include "pkm/cnc/gcode_error.hpp"
#include "pkm/core/error.hpp"

namespace pkm::cnc {

LineReader::LineReader(std::string_view text, std::string file)
    : text_(text), file_(std::move(file)) {}

bool LineReader::next(Block& block) {
  while (!done_ && pos_ < text_.size()) {
    std::size_t eol = text_.find('\n', pos_);
    if (eol == std::string_view::npos) eol = text_.size();
    const std::string_view raw = text_.substr(pos_, eol - pos_);
    pos_ = eol + 1;
    ++line_;
    block.line = line_;
    LineMark mark = LineMark::kNormal;
    try {
      mark = parseLine(raw, block);
    } catch (const GcodeError& e) {
      if (!lenient_) throw IoError(locate(file_, line_, e.what()));
      block.clear();
      block.deferred_error = e.what();
      seen_content_ = true;
      return true;
    }
    if (mark == LineMark::kPercent) {
      if (!seen_content_ && !percent_open_) {
        percent_open_ = true;
        seen_content_ = true;
        continue;
      }
      // A closing '%', or one after a program that did not open with it (after M2, as in
      // LinuxCNC's own files): reading stops there, the rest of the file is ignored. Without
      // M2/M30 before it the program has no end (Interpreter's require_program_end).
      done_ = true;
      break;
    }
    if (block.empty()) continue;
    seen_content_ = true;
    return true;
  }
  return false;
}

namespace {

/// Lines longer than this are not scanned (parseLine rejects them; the answer is then "maybe").
constexpr std::size_t kLongestScannedLine = 4096;

/// True when position `at` of `text` lies in a comment: after an unclosed '(' or a ';' on its line.
/// False for a line longer than kLongestScannedLine (bounded work per candidate).
bool inComment(std::string_view text, std::size_t at) {
  const std::size_t nl = text.rfind('\n', at);
  const std::size_t start = nl == std::string_view::npos ? 0 : nl + 1;
  if (at - start > kLongestScannedLine) return false;
  bool comment = false;
  for (std::size_t i = start; i < at; ++i) {
    if (comment) {
      comment = text[i] != ')';
    } else if (text[i] == '(') {
      comment = true;
    } else if (text[i] == ';') {
      return true;
    }
  }
  return comment;
}

/// True when `letter` occurs in `text` outside comments (memchr finds the candidates).
bool occursOutsideComments(std::string_view text, char letter) {
  const char* begin = text.data();
  const char* end = begin + text.size();
  for (const char* p = begin; p < end;) {
    const void* hit = std::memchr(p, letter, static_cast<std::size_t>(end - p));
    if (hit == nullptr) return false;
    const auto at = static_cast<std::size_t>(static_cast<const char*>(hit) - begin);
    if (!inComment(text, at)) return true;
    p = begin + at + 1;
  }
  return false;
}

}  // namespace

bool LineReader::mayHaveOWords(std::string_view text) {
  return occursOutsideComments(text, 'o') || occursOutsideComments(text, 'O');
}

}  // namespace pkm::cnc
