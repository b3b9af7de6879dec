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

Program Program::parse(std::string_view text, const std::string& file) {
  Program p;
  p.file_ = file;
  p.blocks_.reserve(static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')) + 1);
  LineReader reader(text, file);
  Block block;
  while (reader.next(block)) p.blocks_.push_back(std::move(block));
  p.lines_ = reader.lines();
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

void Program::resolve() {
  struct Open {
    std::size_t index;
    OKind kind;
  };
  std::vector<Open> stack;
  std::size_t current_sub = kNoBlock;
  auto fail = [this](std::size_t i, const std::string& what) {
    throw IoError(locate(file_, blocks_[i].line, what));
  };
  // Innermost open loop (while/do/repeat) with label `name` inside the current sub, or none.
  auto findLoop = [&](const std::string& name) -> std::size_t {
    for (auto it = stack.rbegin(); it != stack.rend(); ++it) {
      if (it->kind == OKind::kSub) break;
      const Block& b = blocks_[it->index];
      if ((it->kind == OKind::kWhile || it->kind == OKind::kDo || it->kind == OKind::kRepeat) &&
          b.o_name == name)
        return it->index;
    }
    return kNoBlock;
  };
  auto closeTop = [&](std::size_t i, OKind opener, const char* what) -> std::size_t {
    Block& b = blocks_[i];
    if (stack.empty() || stack.back().kind != opener ||
        blocks_[stack.back().index].o_name != b.o_name)
      fail(i, fmt::format("{} {} without a matching open statement", oLabel(b.o_name), what));
    const std::size_t open = stack.back().index;
    stack.pop_back();
    return open;
  };
  for (std::size_t i = 0; i < blocks_.size(); ++i) {
    Block& b = blocks_[i];
    switch (b.o_kind) {
      case OKind::kNone:
      case OKind::kCall:
        break;
      case OKind::kSub:
        if (!stack.empty())
          fail(i, fmt::format("{} sub inside another O-word block", oLabel(b.o_name)));
        if (subs_.count(b.o_name) != 0)
          fail(i, fmt::format("{} sub defined twice", oLabel(b.o_name)));
        subs_[b.o_name] = i;
        stack.push_back({i, OKind::kSub});
        current_sub = i;
        break;
      case OKind::kEndSub: {
        const std::size_t open = closeTop(i, OKind::kSub, "endsub");
        blocks_[open].jump = i;
        current_sub = kNoBlock;
        break;
      }
      case OKind::kReturn:
        if (current_sub == kNoBlock)
          fail(i, fmt::format("{} return outside a sub", oLabel(b.o_name)));
        break;
      case OKind::kIf:
        stack.push_back({i, OKind::kIf});
        break;
      case OKind::kElseIf:
      case OKind::kElse: {
        if (stack.empty() || blocks_[stack.back().index].o_name != b.o_name ||
            (stack.back().kind != OKind::kIf && stack.back().kind != OKind::kElseIf))
          fail(i,
               fmt::format("{} {} without a matching if",
                           oLabel(b.o_name),
                           b.o_kind == OKind::kElse ? "else" : "elseif"));
        blocks_[stack.back().index].jump = i;  // previous branch jumps here when false
        stack.back() = {i, b.o_kind == OKind::kElse ? OKind::kElse : OKind::kElseIf};
        break;
      }
      case OKind::kEndIf: {
        if (stack.empty() || blocks_[stack.back().index].o_name != b.o_name ||
            (stack.back().kind != OKind::kIf && stack.back().kind != OKind::kElseIf &&
             stack.back().kind != OKind::kElse))
          fail(i, fmt::format("{} endif without a matching if", oLabel(b.o_name)));
        const std::size_t last = stack.back().index;
        if (blocks_[last].o_kind != OKind::kElse) blocks_[last].jump = i;
        stack.pop_back();
        // Every branch of this chain learns its endif.
        for (std::size_t k = i; k-- > 0;) {
          Block& c = blocks_[k];
          if (c.o_name != b.o_name) continue;
          if (c.o_kind == OKind::kElseIf || c.o_kind == OKind::kElse) c.partner = i;
          if (c.o_kind == OKind::kIf) break;
        }
        break;
      }
      case OKind::kWhile: {
        if (!stack.empty() && stack.back().kind == OKind::kDo &&
            blocks_[stack.back().index].o_name == b.o_name) {
          b.closes_do = true;
          b.partner = stack.back().index;
          blocks_[b.partner].jump = i;
          stack.pop_back();
        } else {
          stack.push_back({i, OKind::kWhile});
        }
        break;
      }
      case OKind::kEndWhile: {
        const std::size_t open = closeTop(i, OKind::kWhile, "endwhile");
        blocks_[open].jump = i;
        b.partner = open;
        break;
      }
      case OKind::kDo:
        stack.push_back({i, OKind::kDo});
        break;
      case OKind::kRepeat:
        stack.push_back({i, OKind::kRepeat});
        break;
      case OKind::kEndRepeat: {
        const std::size_t open = closeTop(i, OKind::kRepeat, "endrepeat");
        blocks_[open].jump = i;
        b.partner = open;
        break;
      }
      case OKind::kBreak:
      case OKind::kContinue: {
        const std::size_t loop = findLoop(b.o_name);
        if (loop == kNoBlock)
          fail(i,
               fmt::format("{} {} outside a loop labelled {}",
                           oLabel(b.o_name),
                           b.o_kind == OKind::kBreak ? "break" : "continue",
                           oLabel(b.o_name)));
        b.partner = loop;
        break;
      }
    }
  }
  if (!stack.empty()) {
    const Block& b = blocks_[stack.back().index];
    const char* closer = "endif";
    switch (stack.back().kind) {
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
  for (Block& b : blocks_)
    if (b.o_kind == OKind::kCall) b.jump = findSub(b.o_name);
}

}  // namespace pkm::cnc
