// The O-word and M98 flow of one run of a program (interpreter.cpp, program_flow.cpp): call
// frames with their active loops. Private to pkm::cnc.
#pragma once

#include <fmt/format.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "interpreter_impl.hpp"
#include "pkm/cnc/gcode_error.hpp"
#include "pkm/cnc/program.hpp"

namespace pkm::cnc {

/// What ProgramFlow::step returns for a call to a sub the program does not define: the caller
/// loads it from a file (ProgramFlow::external() says which, with its arguments).
inline constexpr std::size_t kExternalCall = kNoBlock - 1;
/// What ProgramFlow::step returns when the sub an external call started returns to its caller.
inline constexpr std::size_t kReturnToCaller = kNoBlock - 2;

struct FlowLoop {
  std::size_t start;  // index of while/do/repeat
  std::uint64_t iterations;
  double remaining;  // repeat count left
};

struct FlowFrame {
  std::size_t return_to;  // block after the call
  std::vector<FlowLoop> loops;
  bool fanuc = false;            // an M98 call: ended by M99, no parameter scope
  std::size_t start = kNoBlock;  // M98: the label block, where each repeat starts
  double remaining = 0.0;        // M98: passes left, this one included
  std::uint64_t passes = 0;      // M98: repeats made (runaway guard)
};

/// The O-word flow of one run of a program: the call frames, each with its active loops. With
/// `external_sub`, the run is that of a sub loaded from a file: its endsub/return at the outer
/// level returns kReturnToCaller.
class ProgramFlow {
 public:
  ProgramFlow(const Program& program,
              const InterpreterOptions& options,
              Parameters& params,
              FlowSource& source,
              bool external_sub = false)
      : program_(program),
        blocks_(program.blocks()),
        options_(options),
        params_(params),
        source_(source),
        external_sub_(external_sub) {}

  /// The sub a kExternalCall asks for and its evaluated arguments.
  struct ExternalCall {
    std::string name;
    std::vector<double> args;
  };
  [[nodiscard]] const ExternalCall& external() const { return external_; }

  /// M98 (request.kind 98) or M99 (99) of the block at pc: the block to run next, or kNoBlock
  /// when M99 ends the main program (LinuxCNC's standalone interpreter stops there).
  std::size_t fanuc(const FanucRequest& request, std::size_t pc) {
    if (request.kind == 98) return fanucCall(request, pc);
    FlowFrame& f = frames_.back();
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
        frames_.back().loops.push_back(FlowLoop{pc, 0, 0.0});
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

  void countIteration(FlowLoop& loop) {
    if (++loop.iterations > options_.max_loop_iterations)
      throw GcodeError(
          fmt::format("loop {} exceeded {} iterations (runaway loop guard, InterpreterOptions::"
                      "max_loop_iterations)",
                      oLabel(blocks_[loop.start].o_name),
                      options_.max_loop_iterations));
  }

  FlowLoop& loopOf(std::size_t start) {
    std::vector<FlowLoop>& loops = frames_.back().loops;
    for (auto it = loops.rbegin(); it != loops.rend(); ++it)
      if (it->start == start) return *it;
    throw GcodeError("internal error: loop state missing");
  }

  void leaveLoop(std::size_t start) {
    std::vector<FlowLoop>& loops = frames_.back().loops;
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
    FlowFrame f{pc + 1, {}};
    f.fanuc = true;
    f.start = label;
    f.remaining = request.count;
    frames_.push_back(std::move(f));
    return label + 1;
  }

  std::size_t returnFromSub(const Block& b) {
    if (frames_.size() <= 1 && external_sub_) {
      setReturnValue(b);
      source_.leaveCallLevel();
      params_.popCall();
      return kReturnToCaller;
    }
    if (frames_.size() <= 1) throw GcodeError("return/endsub outside a subroutine call");
    if (frames_.back().fanuc)
      throw GcodeError("endsub/return inside an M98 subprogram: end it with M99");
    const std::size_t pc = frames_.back().return_to;
    frames_.pop_back();
    setReturnValue(b);
    source_.leaveCallLevel();
    params_.popCall();
    return pc;
  }

  /// #<_value> and #<_value_returned> from return/endsub `b` (evaluated in the sub's scope).
  void setReturnValue(const Block& b) {
    const bool has_value = !b.o_args.empty();
    const double value = has_value ? b.o_args[0].evaluate(source_) : 0.0;
    params_.setNamed("_value", value);
    params_.setNamed("_value_returned", has_value ? 1.0 : 0.0);
  }

  std::size_t call(const Block& b, std::size_t pc) {
    std::size_t target = b.jump;
    std::string name = b.o_name;
    if (b.o_label) {  // O[expression] call
      const double v = std::round(b.o_label->evaluate(source_));
      name = fmt::format("{}", static_cast<long long>(v));
      target = program_.findSub(name);
    }
    if (target == kNoBlock && program_.findProgram(name) != kNoBlock)
      throw GcodeError(fmt::format(
          "{} is an M98 subprogram (no sub): call it with M98 P{}", oLabel(name), name));
    if (target == kNoBlock) {  // a sub file: NAME.ngc in the program's folder or the path
      external_.name = name;
      external_.args.clear();
      for (const Expression& e : b.o_args) external_.args.push_back(e.evaluate(source_));
      return kExternalCall;
    }
    if (frames_.size() > options_.max_call_depth)
      throw GcodeError(
          fmt::format("subroutine calls nested deeper than {}", options_.max_call_depth));
    std::vector<double> args;
    args.reserve(b.o_args.size());
    for (const Expression& e : b.o_args) args.push_back(e.evaluate(source_));
    params_.pushCall(args);
    frames_.push_back(FlowFrame{pc + 1, {}});
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
    FlowLoop& loop = loopOf(b.partner);
    if (truth(b)) {
      countIteration(loop);
      return b.partner + 1;
    }
    leaveLoop(b.partner);
    return pc + 1;
  }

  std::size_t whileLoop(const Block& b, std::size_t pc) {
    std::vector<FlowLoop>& loops = frames_.back().loops;
    if (loops.empty() || loops.back().start != pc) loops.push_back(FlowLoop{pc, 0, 0.0});
    if (truth(b)) return pc + 1;
    leaveLoop(pc);
    return b.jump + 1;
  }

  std::size_t repeat(const Block& b, std::size_t pc) {
    const double n = std::floor(b.o_args[0].evaluate(source_));
    if (n < 1.0) return b.jump + 1;
    frames_.back().loops.push_back(FlowLoop{pc, 0, n});
    return pc + 1;
  }

  std::size_t endRepeat(const Block& b, std::size_t pc) {
    FlowLoop& loop = loopOf(b.partner);
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
  FlowSource& source_;  // the parameters' source; M73's modal state
  std::vector<FlowFrame> frames_ = std::vector<FlowFrame>(1, FlowFrame{kNoBlock, {}});
  bool external_sub_ = false;
  ExternalCall external_;
};

}  // namespace pkm::cnc
