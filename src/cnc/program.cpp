// Program reading and O-word structure resolution (LinuxCNC 2.9 "O Codes": matching labels,
// subroutines not nested, loops closed by the statement with the same label).
#include "pkm/cnc/program.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "pkm/cnc/gcode_error.hpp"
#include "pkm/cnc/line_reader.hpp"
#include "pkm/core/error.hpp"

namespace pkm::cnc {

namespace {

/// Matches the O-word statements of a program's blocks: sets each opener's `jump` and each
/// closer's `partner`, records the subs, and throws pkm::IoError "FILE:LINE: message" for a
/// statement without its partner.
class StructureResolver {
 public:
  StructureResolver(std::vector<Block>& blocks,
                    std::unordered_map<std::string, std::size_t>& subs,
                    const std::string& file)
      : blocks_(blocks), subs_(subs), file_(file) {}

  void run() {
    for (std::size_t i = 0; i < blocks_.size(); ++i) statement(i);
    if (!stack_.empty()) failUnclosed();
  }

 private:
  struct Open {
    std::size_t index;
    OKind kind;
  };

  [[noreturn]] void fail(std::size_t i, const std::string& what) const {
    throw IoError(locate(file_, blocks_[i].line, what));
  }

  void statement(std::size_t i) {
    Block& b = blocks_[i];
    switch (b.o_kind) {
      case OKind::kNone:
      case OKind::kCall:
      case OKind::kProgram:
        break;
      case OKind::kSub:
        sub(i);
        break;
      case OKind::kEndSub:
        blocks_[closeTop(i, OKind::kSub, "endsub")].jump = i;
        current_sub_ = kNoBlock;
        break;
      case OKind::kReturn:
        if (current_sub_ == kNoBlock)
          fail(i, fmt::format("{} return outside a sub", oLabel(b.o_name)));
        break;
      case OKind::kIf:
        stack_.push_back({i, OKind::kIf});
        break;
      case OKind::kElseIf:
      case OKind::kElse:
        elseBranch(i);
        break;
      case OKind::kEndIf:
        endIf(i);
        break;
      case OKind::kWhile:
        whileStatement(i);
        break;
      case OKind::kEndWhile:
        closeLoop(i, OKind::kWhile, "endwhile");
        break;
      case OKind::kDo:
        stack_.push_back({i, OKind::kDo});
        break;
      case OKind::kRepeat:
        stack_.push_back({i, OKind::kRepeat});
        break;
      case OKind::kEndRepeat:
        closeLoop(i, OKind::kRepeat, "endrepeat");
        break;
      case OKind::kBreak:
      case OKind::kContinue:
        breakOrContinue(i);
        break;
    }
  }

  // Innermost open loop (while/do/repeat) with label `name` inside the current sub, or none.
  [[nodiscard]] std::size_t findLoop(const std::string& name) const {
    for (auto it = stack_.rbegin(); it != stack_.rend(); ++it) {
      if (it->kind == OKind::kSub) break;
      const Block& b = blocks_[it->index];
      if ((it->kind == OKind::kWhile || it->kind == OKind::kDo || it->kind == OKind::kRepeat) &&
          b.o_name == name)
        return it->index;
    }
    return kNoBlock;
  }

  /// Pops the open statement that block `i` closes (kind `opener`, same label); returns its index.
  std::size_t closeTop(std::size_t i, OKind opener, const char* what) {
    const Block& b = blocks_[i];
    if (stack_.empty() || stack_.back().kind != opener ||
        blocks_[stack_.back().index].o_name != b.o_name)
      fail(i, fmt::format("{} {} without a matching open statement", oLabel(b.o_name), what));
    const std::size_t open = stack_.back().index;
    stack_.pop_back();
    return open;
  }

  void sub(std::size_t i) {
    const Block& b = blocks_[i];
    if (!stack_.empty())
      fail(i, fmt::format("{} sub inside another O-word block", oLabel(b.o_name)));
    if (subs_.count(b.o_name) != 0) fail(i, fmt::format("{} sub defined twice", oLabel(b.o_name)));
    subs_[b.o_name] = i;
    stack_.push_back({i, OKind::kSub});
    current_sub_ = i;
  }

  void elseBranch(std::size_t i) {
    const Block& b = blocks_[i];
    if (stack_.empty() || blocks_[stack_.back().index].o_name != b.o_name ||
        (stack_.back().kind != OKind::kIf && stack_.back().kind != OKind::kElseIf))
      fail(i,
           fmt::format("{} {} without a matching if",
                       oLabel(b.o_name),
                       b.o_kind == OKind::kElse ? "else" : "elseif"));
    blocks_[stack_.back().index].jump = i;  // previous branch jumps here when false
    stack_.back() = {i, b.o_kind == OKind::kElse ? OKind::kElse : OKind::kElseIf};
  }

  void endIf(std::size_t i) {
    const Block& b = blocks_[i];
    if (stack_.empty() || blocks_[stack_.back().index].o_name != b.o_name ||
        (stack_.back().kind != OKind::kIf && stack_.back().kind != OKind::kElseIf &&
         stack_.back().kind != OKind::kElse))
      fail(i, fmt::format("{} endif without a matching if", oLabel(b.o_name)));
    const std::size_t last = stack_.back().index;
    if (blocks_[last].o_kind != OKind::kElse) blocks_[last].jump = i;
    stack_.pop_back();
    // Every branch of this chain learns its endif.
    for (std::size_t k = i; k-- > 0;) {
      Block& c = blocks_[k];
      if (c.o_name != b.o_name) continue;
      if (c.o_kind == OKind::kElseIf || c.o_kind == OKind::kElse) c.partner = i;
      if (c.o_kind == OKind::kIf) break;
    }
  }

  /// A while: the end of an open do loop with its label, else the start of a while loop.
  void whileStatement(std::size_t i) {
    Block& b = blocks_[i];
    if (!stack_.empty() && stack_.back().kind == OKind::kDo &&
        blocks_[stack_.back().index].o_name == b.o_name) {
      b.closes_do = true;
      b.partner = stack_.back().index;
      blocks_[b.partner].jump = i;
      stack_.pop_back();
    } else {
      stack_.push_back({i, OKind::kWhile});
    }
  }

  /// endwhile / endrepeat: closes the loop `opener` and links both ends.
  void closeLoop(std::size_t i, OKind opener, const char* what) {
    const std::size_t open = closeTop(i, opener, what);
    blocks_[open].jump = i;
    blocks_[i].partner = open;
  }

  void breakOrContinue(std::size_t i) {
    Block& b = blocks_[i];
    const std::size_t loop = findLoop(b.o_name);
    if (loop == kNoBlock)
      fail(i,
           fmt::format("{} {} outside a loop labelled {}",
                       oLabel(b.o_name),
                       b.o_kind == OKind::kBreak ? "break" : "continue",
                       oLabel(b.o_name)));
    b.partner = loop;
  }

  /// Throws for the innermost statement left open at the end of the program.
  [[noreturn]] void failUnclosed() const {
    const Block& b = blocks_[stack_.back().index];
    const char* closer = "endif";
    switch (stack_.back().kind) {
      case OKind::kSub:
        closer = "endsub";
        break;
      case OKind::kWhile:
        closer = "endwhile";
        break;
      case OKind::kDo:
        closer = "while";
        break;
      case OKind::kRepeat:
        closer = "endrepeat";
        break;
      default:
        break;
    }
    throw IoError(locate(
        file_,
        b.line,
        fmt::format(
            "{} is not closed: no matching {} {}", oLabel(b.o_name), oLabel(b.o_name), closer)));
  }

  std::vector<Block>& blocks_;
  std::unordered_map<std::string, std::size_t>& subs_;
  const std::string& file_;
  std::vector<Open> stack_;
  std::size_t current_sub_ = kNoBlock;
};

}  // namespace

namespace {

/// Whether the text read so far has an M2 or M30: LinuxCNC stops reading at the program end it
/// executes, so a line after one that does not parse is an error only if it is ever reached (a
/// conditional end, a sub defined after the main program).
class EndTracker {
 public:
  /// Takes the next block; true once an M2/M30 (not block-deleted) has been read.
  bool after(const Block& b) {
    if (!b.block_delete)
      for (const Word& w : b.words)
        if (w.letter == 'm' && w.value.isConstant()) {
          const double m = w.value.constantValue();
          ended_ = ended_ || m == 2.0 || m == 30.0;
        }
    return ended_;
  }

 private:
  bool ended_ = false;
};

}  // namespace

Program Program::parse(std::string_view text, const std::string& file) {
  Program p;
  p.file_ = file;
  p.blocks_.reserve(static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) + 1);
  LineReader reader(text, file);
  Block block;
  EndTracker end;
  while (reader.next(block)) {
    reader.setLenient(end.after(block));
    p.blocks_.push_back(std::move(block));
  }
  p.lines_ = reader.lines();
  p.closed_by_percent_ = reader.closedByPercent();
  p.resolve();
  return p;
}

std::string Program::readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(fmt::format("{}: cannot open G-code file", path));
  std::string text;
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  in.seekg(0, std::ios::beg);
  if (size > 0) {
    text.resize(static_cast<std::size_t>(size));
    in.read(text.data(), size);
    text.resize(static_cast<std::size_t>(in.gcount()));
  } else {  // not seekable (a pipe): read as a stream
    std::ostringstream ss;
    ss << in.rdbuf();
    text = ss.str();
  }
  return text;
}

Program Program::load(const std::string& path) { return parse(readFile(path), path); }

std::size_t Program::findSub(const std::string& name) const {
  const auto it = subs_.find(name);
  return it == subs_.end() ? kNoBlock : it->second;
}

std::size_t Program::findProgram(const std::string& name) const {
  const auto it = programs_.find(programKey(name));
  return it == programs_.end() ? kNoBlock : it->second;
}

std::string Program::programKey(const std::string& name) {
  if (name.empty() || name.find_first_not_of("0123456789") != std::string::npos) return name;
  const std::size_t first = name.find_first_not_of('0');
  return first == std::string::npos ? "0" : name.substr(first);
}

void Program::resolve() {
  StructureResolver(blocks_, subs_, file_).run();
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    Block& b = blocks_[i];
    if (b.o_kind == OKind::kCall && !b.o_label) b.jump = findSub(b.o_name);
    if (b.o_kind == OKind::kProgram) programs_.emplace(programKey(b.o_name), i);  // first wins
  }
}

}  // namespace pkm::cnc
