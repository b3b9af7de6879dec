// Program flow of the interpreter: the block loop and O-word control (LinuxCNC 2.9 "O Codes":
// sub/endsub/call/return with #1-#30 arguments and #<_value> return values, if/elseif/else/endif,
// while/endwhile, do/while, repeat/endrepeat, break/continue), with an iteration guard per loop.
#include "pkm/cnc/interpreter.hpp"

#include <fmt/format.h>

#include "interpreter_impl.hpp"
#include "pkm/cnc/gcode_error.hpp"
#include "pkm/core/error.hpp"

namespace pkm::cnc {

namespace {

struct Loop {
  std::size_t start;  // index of while/do/repeat
  std::uint64_t iterations;
  double remaining;  // repeat count left
};

struct Frame {
  std::size_t return_to;  // block after the call
  std::vector<Loop> loops;
};

}  // namespace

Interpreter::Interpreter(InterpreterOptions options)
    : impl_(std::make_unique<Impl>(std::move(options))) {}
Interpreter::~Interpreter() = default;
const MachineState& Interpreter::state() const { return impl_->st; }

RunSummary Interpreter::run(const Program& program, MoveSink& sink) {
  Impl& s = *impl_;
  s.summary = RunSummary{};
  s.report_blocks = sink.wantsBlocks();
  const std::vector<Block>& blocks = program.blocks();
  std::vector<Frame> frames(1, Frame{kNoBlock, {}});
  std::size_t pc = 0;
  std::size_t line = 0;
  auto truth = [&](const Block& b) { return b.o_args.at(0).evaluate(s) != 0.0; };
  auto countIteration = [&](Loop& loop) {
    if (++loop.iterations > s.options.max_loop_iterations)
      throw GcodeError(
          fmt::format("loop {} exceeded {} iterations (runaway loop guard, InterpreterOptions::"
                      "max_loop_iterations)",
                      oLabel(blocks[loop.start].o_name),
                      s.options.max_loop_iterations));
  };
  auto loopOf = [&](std::size_t start) -> Loop& {
    std::vector<Loop>& loops = frames.back().loops;
    for (auto it = loops.rbegin(); it != loops.rend(); ++it)
      if (it->start == start) return *it;
    throw GcodeError("internal error: loop state missing");
  };
  auto leaveLoop = [&](std::size_t start) {
    std::vector<Loop>& loops = frames.back().loops;
    while (!loops.empty()) {
      const bool done = loops.back().start == start;
      loops.pop_back();
      if (done) break;
    }
  };
  auto returnFromSub = [&](const Block& b) {
    if (frames.size() <= 1) throw GcodeError("return/endsub outside a subroutine call");
    bool has_value = !b.o_args.empty();
    const double value = has_value ? b.o_args[0].evaluate(s) : 0.0;
    pc = frames.back().return_to;
    frames.pop_back();
    s.params.popCall();
    s.params.setNamed("_value", value);
    s.params.setNamed("_value_returned", has_value ? 1.0 : 0.0);
  };
  try {
    while (pc < blocks.size()) {
      const Block& b = blocks[pc];
      line = b.line;
      ++s.summary.blocks;
      if (b.block_delete && s.options.block_delete) {
        ++pc;
        continue;
      }
      s.block_index = pc;
      if (s.report_blocks && b.o_kind != OKind::kNone) {
        s.evaluated.clear();
        sink.onBlock(b, pc, s.evaluated);
      }
      switch (b.o_kind) {
        case OKind::kNone:
          if (!s.execute(b, sink)) {
            s.summary.ended_by_m2 = true;
            return s.summary;
          }
          ++pc;
          break;
        case OKind::kSub:
          pc = b.jump + 1;  // definitions are skipped when reached in sequence
          break;
        case OKind::kEndSub:
        case OKind::kReturn:
          returnFromSub(b);
          break;
        case OKind::kCall: {
          if (b.jump == kNoBlock)
            throw GcodeError(
                fmt::format("call to undefined subroutine {} (subroutine files are "
                            "not searched)",
                            oLabel(b.o_name)));
          if (frames.size() > s.options.max_call_depth)
            throw GcodeError(
                fmt::format("subroutine calls nested deeper than {}", s.options.max_call_depth));
          std::vector<double> args;
          args.reserve(b.o_args.size());
          for (const Expression& e : b.o_args) args.push_back(e.evaluate(s));
          s.params.pushCall(args);
          frames.push_back(Frame{pc + 1, {}});
          pc = b.jump + 1;
          break;
        }
        case OKind::kIf:
        case OKind::kElseIf: {
          if (b.o_kind == OKind::kElseIf) {  // reached after a taken branch: skip to endif
            pc = b.partner + 1;
            break;
          }
          std::size_t k = pc;
          while (true) {
            const Block& c = blocks[k];
            if (c.o_kind == OKind::kEndIf) {
              pc = k + 1;
              break;
            }
            if (c.o_kind == OKind::kElse || truth(c)) {
              pc = k + 1;
              break;
            }
            k = c.jump;
          }
          break;
        }
        case OKind::kElse:
          pc = b.partner + 1;
          break;
        case OKind::kEndIf:
          ++pc;
          break;
        case OKind::kWhile: {
          if (b.closes_do) {
            Loop& loop = loopOf(b.partner);
            if (truth(b)) {
              countIteration(loop);
              pc = b.partner + 1;
            } else {
              leaveLoop(b.partner);
              ++pc;
            }
            break;
          }
          std::vector<Loop>& loops = frames.back().loops;
          if (loops.empty() || loops.back().start != pc) loops.push_back(Loop{pc, 0, 0.0});
          if (truth(b)) {
            ++pc;
          } else {
            leaveLoop(pc);
            pc = b.jump + 1;
          }
          break;
        }
        case OKind::kEndWhile:
          countIteration(loopOf(b.partner));
          pc = b.partner;
          break;
        case OKind::kDo:
          frames.back().loops.push_back(Loop{pc, 0, 0.0});
          ++pc;
          break;
        case OKind::kRepeat: {
          const double n = std::floor(b.o_args[0].evaluate(s));
          if (n < 1.0) {
            pc = b.jump + 1;
          } else {
            frames.back().loops.push_back(Loop{pc, 0, n});
            ++pc;
          }
          break;
        }
        case OKind::kEndRepeat: {
          Loop& loop = loopOf(b.partner);
          countIteration(loop);
          loop.remaining -= 1.0;
          if (loop.remaining >= 1.0) {
            pc = b.partner + 1;
          } else {
            leaveLoop(b.partner);
            ++pc;
          }
          break;
        }
        case OKind::kBreak: {
          const Block& open = blocks[b.partner];
          leaveLoop(b.partner);
          pc = open.jump + 1;
          break;
        }
        case OKind::kContinue: {
          const Block& open = blocks[b.partner];
          if (open.o_kind == OKind::kWhile) {
            countIteration(loopOf(b.partner));
            pc = b.partner;  // re-test the condition
          } else {
            pc = open.jump;  // do: the closing while; repeat: endrepeat
          }
          break;
        }
      }
    }
  } catch (const GcodeError& e) {
    throw IoError(locate(program.file(), line, e.what()));
  }
  return s.summary;
}

RunSummary Interpreter::runStream(LineReader& reader, MoveSink& sink) {
  Impl& s = *impl_;
  s.summary = RunSummary{};
  s.report_blocks = sink.wantsBlocks();
  s.block_index = kNoBlock;  // streamed blocks have no index in a Program
  Block b;
  while (reader.next(b)) {
    try {
      if (b.o_kind != OKind::kNone)
        throw GcodeError(fmt::format(
            "{} statement: O-words need the whole program (read it with Program::parse)",
            oLabel(b.o_name)));
      ++s.summary.blocks;
      if (b.block_delete && s.options.block_delete) continue;
      if (!s.execute(b, sink)) {
        s.summary.ended_by_m2 = true;
        while (reader.next(b)) {  // the rest is not run, but must still be well formed
        }
        return s.summary;
      }
    } catch (const GcodeError& e) {
      throw IoError(locate(reader.file(), b.line, e.what()));
    }
  }
  return s.summary;
}

}  // namespace pkm::cnc
