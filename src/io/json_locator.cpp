#include "pkm/io/json_locator.hpp"

#include <vector>

namespace pkm::io {

namespace {

/// A recursive-descent walk over valid JSON that records where each value starts.
class Scanner {
 public:
  Scanner(std::string_view text, std::unordered_map<std::string, std::size_t>& lines)
      : text_(text), lines_(lines) {}

  void run() {
    skipSpace();
    value("");
  }

 private:
  void skipSpace() {
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '\n') ++line_;
      if (c != ' ' && c != '\t' && c != '\n' && c != '\r') break;
      ++pos_;
    }
  }

  std::string readString() {  // at the opening quote
    std::string out;
    ++pos_;
    while (pos_ < text_.size() && text_[pos_] != '"') {
      if (text_[pos_] == '\\' && pos_ + 1 < text_.size()) {
        out += text_[pos_ + 1];
        pos_ += 2;
        continue;
      }
      out += text_[pos_++];
    }
    ++pos_;
    return out;
  }

  static std::string escape(const std::string& key) {
    std::string out;
    for (char c : key) {
      if (c == '~')
        out += "~0";
      else if (c == '/')
        out += "~1";
      else
        out += c;
    }
    return out;
  }

  /// Skips a whole value without recording pointers (nesting deeper than kMaxDepth).
  void skipValue() {
    int depth = 0;
    while (pos_ < text_.size()) {
      const char c = text_[pos_];
      if (c == '"') {
        readString();
        if (depth == 0) return;
        continue;
      }
      if (depth == 0 && (c == ',' || c == '}' || c == ']')) return;  // end of a scalar
      if (c == '\n') ++line_;
      ++pos_;
      if (c == '{' || c == '[') ++depth;
      if ((c == '}' || c == ']') && --depth == 0) return;
    }
  }

  void value(const std::string& pointer) {
    if (pos_ >= text_.size()) return;
    if (depth_ >= kMaxDepth) {
      skipValue();
      return;
    }
    lines_.emplace(pointer, line_);
    const char c = text_[pos_];
    if (c == '{') {
      ++depth_;
      ++pos_;
      skipSpace();
      while (pos_ < text_.size() && text_[pos_] != '}') {
        if (text_[pos_] != '"') {
          --depth_;
          return;
        }
        const std::string key = readString();
        skipSpace();
        if (pos_ < text_.size() && text_[pos_] == ':') ++pos_;
        skipSpace();
        value(pointer + "/" + escape(key));
        skipSpace();
        if (pos_ < text_.size() && text_[pos_] == ',') ++pos_;
        skipSpace();
      }
      ++pos_;
      --depth_;
    } else if (c == '[') {
      ++depth_;
      ++pos_;
      skipSpace();
      for (std::size_t i = 0; pos_ < text_.size() && text_[pos_] != ']'; ++i) {
        const std::size_t before = pos_;
        value(pointer + "/" + std::to_string(i));
        if (pos_ == before) {  // invalid input (e.g. "[}"): no progress, stop here
          --depth_;
          return;
        }
        skipSpace();
        if (pos_ < text_.size() && text_[pos_] == ',') ++pos_;
        skipSpace();
      }
      ++pos_;
      --depth_;
    } else if (c == '"') {
      readString();
    } else {
      while (pos_ < text_.size() && text_[pos_] != ',' && text_[pos_] != '}' &&
             text_[pos_] != ']' && text_[pos_] != ' ' && text_[pos_] != '\n' &&
             text_[pos_] != '\r' && text_[pos_] != '\t')
        ++pos_;
    }
  }

  std::string_view text_;
  std::unordered_map<std::string, std::size_t>& lines_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
  int depth_ = 0;
  static constexpr int kMaxDepth = 512;  ///< deeper values are skipped (no recursion without bound)
};

}  // namespace

JsonLocator::JsonLocator(std::string_view text) { Scanner(text, lines_).run(); }

std::size_t JsonLocator::line(std::string pointer) const {
  while (true) {
    const auto it = lines_.find(pointer);
    if (it != lines_.end()) return it->second;
    if (pointer.empty()) return 0;
    const auto slash = pointer.rfind('/');
    pointer.resize(slash == std::string::npos ? 0 : slash);
  }
}

}  // namespace pkm::io
