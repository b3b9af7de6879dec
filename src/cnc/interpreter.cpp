// Program flow of the interpreter: the block loop and O-word control (LinuxCNC 2.9 "O Codes":
// sub/endsub/call/return with #1-#30 arguments and #<_value> return values, if/elseif/else/endif,
// while/endwhile, do/while, repeat/endrepeat, break/continue, O[expression] call; "Fanuc-Style
// Numbered Programs": M98 P L calls of O-labelled subprograms ended by M99, sharing the
// parameters), with an iteration guard per loop.
#include "pkm/cnc/interpreter.hpp"

#include <fmt/format.h>

#include <cmath>
#include <utility>

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
  bool fanuc = false;            // an M98 call: ended by M99, no parameter scope
  std::size_t start = kNoBlock;  // M98: the label block, where each repeat starts
  double remaining = 0.0;        // M98: passes left, this one included
  std::uint64_t passes = 0;      // M98: repeats made (runaway guard)
};

/// The O-word flow of one run of a program: the call frames, each with its active loops.
class ProgramFlow {
 public:
  ProgramFlow(const Program& program,
              const InterpreterOptions& options,
              Parameters& params,
              ParameterSource& source)
      : program_(program),
        blocks_(program.blocks()),
        options_(options),
        params_(params),
        source_(source) {}

  /// M98 (request.kind 98) or M99 (99) of the block at pc: the block to run next, or kNoBlock
  /// when M99 ends the main program (LinuxCNC's standalone interpreter stops there).
  std::size_t fanuc(const FanucRequest& request, std::size_t pc) {
    if (request.kind == 98) return fanucCall(request, pc);
    Frame& f = frames_.back();
    if (frames_.size() <= 1) return kNoBlock;
    if (!f.fanuc) throw GcodeError("M99 inside an O-word sub: end it with endsub or return");
    f.remaining -= 1.0;
    if (f.remaining >= 1.0) {
      if (++f.passes > options_.max_loop_iterations)
        throw GcodeError(fmt::format("M98 repeats exceeded {} passes (runaway loop guard)",
                                     options_.max_loop_iterations));
      f.loops.clear();
      return f.start + 1;
    }
    const std::size_t back = f.return_to;
    frames_.pop_back();
    return back;
  }

  /// Performs the O-word statement blocks[pc]; returns the index of the block to run next.
  std::size_t step(std::size_t pc) {
    const Block& b = blocks_[pc];
    switch (b.o_kind) {
      case OKind::kNone:
        break;
      case OKind::kSub:
        return b.jump + 1;  // definitions are skipped when reached in sequence
      case OKind::kEndSub:
      case OKind::kReturn:
        return returnFromSub(b);
      case OKind::kCall:
        return call(b, pc);
      case OKind::kIf:
        return branch(pc);
      case OKind::kElseIf:  // reached after a taken branch: skip to endif
      case OKind::kElse:
        return b.partner + 1;
      case OKind::kEndIf:
      case OKind::kProgram:  // a label reached in sequence
        return pc + 1;
      case OKind::kWhile:
        return b.closes_do ? closeDo(b, pc) : whileLoop(b, pc);
      case OKind::kEndWhile:
        countIteration(loopOf(b.partner));
        return b.partner;
      case OKind::kDo:
        frames_.back().loops.push_back(Loop{pc, 0, 0.0});
        return pc + 1;
      case OKind::kRepeat:
        return repeat(b, pc);
      case OKind::kEndRepeat:
        return endRepeat(b, pc);
      case OKind::kBreak:
        leaveLoop(b.partner);
        return blocks_[b.partner].jump + 1;
      case OKind::kContinue:
        return continueLoop(b);
    }
    return pc + 1;
  }

 private:
  bool truth(const Block& b) { return b.o_args.at(0).evaluate(source_) != 0.0; }

  void countIteration(Loop& loop) {
    if (++loop.iterations > options_.max_loop_iterations)
      throw GcodeError(
          fmt::format("loop {} exceeded {} iterations (runaway loop guard, InterpreterOptions::"
                      "max_loop_iterations)",
                      oLabel(blocks_[loop.start].o_name),
                      options_.max_loop_iterations));
  }

  Loop& loopOf(std::size_t start) {
    std::vector<Loop>& loops = frames_.back().loops;
    for (auto it = loops.rbegin(); it != loops.rend(); ++it)
      if (it->start == start) return *it;
    throw GcodeError("internal error: loop state missing");
  }

  void leaveLoop(std::size_t start) {
    std::vector<Loop>& loops = frames_.back().loops;
    while (!loops.empty()) {
      const bool done = loops.back().start == start;
      loops.pop_back();
      if (done) break;
    }
  }

  std::size_t fanucCall(const FanucRequest& request, std::size_t pc) {
    const std::size_t label = program_.findProgram(request.target);
    if (label == kNoBlock) {
      const std::size_t sub = program_.findSub(request.target);
      throw GcodeError(sub != kNoBlock ? fmt::format("M98 P{}: o{} is an O-word sub; call it with "
                                                     "o{} call",
                                                     request.target,
                                                     request.target,
                                                     request.target)
                                       : fmt::format("M98 P{}: no subprogram O{} in the program",
                                                     request.target,
                                                     request.target));
    }
    if (request.count < 1.0) return pc + 1;
    if (frames_.size() > options_.max_call_depth)
      throw GcodeError(
          fmt::format("subroutine calls nested deeper than {}", options_.max_call_depth));
    Frame f{pc + 1, {}};
    f.fanuc = true;
    f.start = label;
    f.remaining = request.count;
    frames_.push_back(std::move(f));
    return label + 1;
  }

  std::size_t returnFromSub(const Block& b) {
    if (frames_.size() <= 1) throw GcodeError("return/endsub outside a subroutine call");
    if (frames_.back().fanuc)
      throw GcodeError("endsub/return inside an M98 subprogram: end it with M99");
    bool has_value = !b.o_args.empty();
    const double value = has_value ? b.o_args[0].evaluate(source_) : 0.0;
    const std::size_t pc = frames_.back().return_to;
    frames_.pop_back();
    params_.popCall();
    params_.setNamed("_value", value);
    params_.setNamed("_value_returned", has_value ? 1.0 : 0.0);
    return pc;
  }

  std::size_t call(const Block& b, std::size_t pc) {
    std::size_t target = b.jump;
    std::string name = b.o_name;
    if (b.o_label) {  // O[expression] call
      const double v = std::round(b.o_label->evaluate(source_));
      name = fmt::format("{}", static_cast<long long>(v));
      target = program_.findSub(name);
    }
    if (target == kNoBlock)
      throw GcodeError(program_.findProgram(name) != kNoBlock
                           ? fmt::format("{} is an M98 subprogram (no sub): call it with M98 P{}",
                                         oLabel(name),
                                         name)
                           : fmt::format("call to undefined subroutine {} (subroutine files are "
                                         "not searched)",
                                         oLabel(name)));
    if (frames_.size() > options_.max_call_depth)
      throw GcodeError(
          fmt::format("subroutine calls nested deeper than {}", options_.max_call_depth));
    std::vector<double> args;
    args.reserve(b.o_args.size());
    for (const Expression& e : b.o_args) args.push_back(e.evaluate(source_));
    params_.pushCall(args);
    frames_.push_back(Frame{pc + 1, {}});
    return target + 1;
  }

  /// if: the first branch whose condition holds (or else), past endif when none does.
  std::size_t branch(std::size_t pc) {
    std::size_t k = pc;
    while (true) {
      const Block& c = blocks_[k];
      if (c.o_kind == OKind::kEndIf) return k + 1;
      if (c.o_kind == OKind::kElse || truth(c)) return k + 1;
      k = c.jump;
    }
  }

  /// The while that closes a do loop.
  std::size_t closeDo(const Block& b, std::size_t pc) {
    Loop& loop = loopOf(b.partner);
    if (truth(b)) {
      countIteration(loop);
      return b.partner + 1;
    }
    leaveLoop(b.partner);
    return pc + 1;
  }

  std::size_t whileLoop(const Block& b, std::size_t pc) {
    std::vector<Loop>& loops = frames_.back().loops;
    if (loops.empty() || loops.back().start != pc) loops.push_back(Loop{pc, 0, 0.0});
    if (truth(b)) return pc + 1;
    leaveLoop(pc);
    return b.jump + 1;
  }

  std::size_t repeat(const Block& b, std::size_t pc) {
    const double n = std::floor(b.o_args[0].evaluate(source_));
    if (n < 1.0) return b.jump + 1;
    frames_.back().loops.push_back(Loop{pc, 0, n});
    return pc + 1;
  }

  std::size_t endRepeat(const Block& b, std::size_t pc) {
    Loop& loop = loopOf(b.partner);
    countIteration(loop);
    loop.remaining -= 1.0;
    if (loop.remaining >= 1.0) return b.partner + 1;
    leaveLoop(b.partner);
    return pc + 1;
  }

  std::size_t continueLoop(const Block& b) {
    const Block& open = blocks_[b.partner];
    if (open.o_kind == OKind::kWhile) {
      countIteration(loopOf(b.partner));
      return b.partner;  // re-test the condition
    }
    return open.jump;  // do: the closing while; repeat: endrepeat
  }

  const Program& program_;
  const std::vector<Block>& blocks_;
  const InterpreterOptions& options_;
  Parameters& params_;
  ParameterSource& source_;
  std::vector<Frame> frames_ = std::vector<Frame>(1, Frame{kNoBlock, {}});
};

}  // namespace

namespace {
constexpr const char* kNoProgramEnd =
    "the file ended with no percent sign or program end (M2, M30), which LinuxCNC refuses";
}  // namespace

Interpreter::Interpreter(InterpreterOptions options)
    : impl_(std::make_unique<Impl>(std::move(options))) {
  const InterpreterOptions& o = impl_->options;
  o.arc.validate();
  impl_->loadParameters();
  if (o.startup_code.empty()) return;
  const std::string where = o.startup_source.empty() ? "" : o.startup_source + ": ";
  MoveCollector none;
  const bool require_end = o.require_program_end;
  impl_->options.require_program_end = false;  // start-up code is a line, not a program
  try {
    (void)run(Program::parse(o.startup_code, "RS274NGC_STARTUP_CODE"), none);
  } catch (const IoError& e) {
    throw IoError(where + e.what());
  }
  impl_->options.require_program_end = require_end;
  if (!none.moves.empty() || !none.dwells.empty())
    throw IoError(where + "RS274NGC_STARTUP_CODE moves the machine; it may set modes only");
}
Interpreter::~Interpreter() = default;
const MachineState& Interpreter::state() const { return impl_->st; }

RunSummary Interpreter::run(const Program& program, MoveSink& sink) {
  Impl& s = *impl_;
  s.summary = RunSummary{};
  s.report_blocks = sink.wantsBlocks();
  const std::vector<Block>& blocks = program.blocks();
  ProgramFlow flow(program, s.options, s.params, s);
  std::size_t pc = 0;
  std::size_t line = 0;
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
      if (b.o_kind == OKind::kNone) {
        if (!s.execute(b, sink)) {
          s.summary.ended_by_m2 = true;
          return s.summary;
        }
        if (s.fanuc.kind == 0) {
          ++pc;
          continue;
        }
        const FanucRequest request = std::exchange(s.fanuc, FanucRequest{});
        pc = flow.fanuc(request, pc);
        if (pc == kNoBlock) {  // M99 in the main program
          s.summary.ended_by_m2 = true;
          return s.summary;
        }
        continue;
      }
      if (s.report_blocks) {
        s.evaluated.clear();
        sink.onBlock(b, pc, s.evaluated);
      }
      pc = flow.step(pc);
    }
  } catch (const GcodeError& e) {
    throw IoError(locate(program.file(), line, e.what()));
  }
  if (s.options.require_program_end && !program.closedByPercent())
    throw IoError(locate(program.file(), program.lineCount(), kNoProgramEnd));
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
      if (std::exchange(s.fanuc, FanucRequest{}).kind != 0)
        throw GcodeError("M98/M99 need the whole program (read it with Program::parse)");
    } catch (const GcodeError& e) {
      throw IoError(locate(reader.file(), b.line, e.what()));
    }
  }
  if (s.options.require_program_end && !reader.closedByPercent())
    throw IoError(locate(reader.file(), reader.lines(), kNoProgramEnd));
  return s.summary;
}

}  // namespace pkm::cnc
