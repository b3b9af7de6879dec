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
#include "program_flow.hpp"

namespace pkm::cnc {

namespace {
constexpr const char* kNoProgramEnd =
    "the file ended with no percent sign or program end (M2, M30), which LinuxCNC refuses";

/// Forwards to a sink and refuses the motion past InterpreterOptions::max_moves.
class MoveBudget : public MoveSink {
 public:
  MoveBudget(MoveSink& inner, std::size_t max) : inner_(inner), max_(max) {}
  [[nodiscard]] bool wantsBlocks() const override { return inner_.wantsBlocks(); }
  void onBlock(const Block& b, std::size_t index, const std::vector<EvaluatedWord>& w) override {
    inner_.onBlock(b, index, w);
  }
  void onMove(const Move& move) override {
    if (max_ != 0 && ++moves_ > max_)
      throw GcodeError(
          fmt::format("the program makes more than {} motions, the most this run "
                      "allows (its point budget, --max-points); a runaway loop?",
                      max_));
    inner_.onMove(move);
  }
  void onDwell(std::size_t line, double seconds) override { inner_.onDwell(line, seconds); }
  void onCycleAction(std::size_t line, CycleAction action) override {
    inner_.onCycleAction(line, action);
  }
  void onToolChange(std::size_t line, int tool) override { inner_.onToolChange(line, tool); }
  void onMessage(std::size_t line, CommentKind kind, const std::string& text) override {
    inner_.onMessage(line, kind, text);
  }

 private:
  MoveSink& inner_;
  std::size_t max_;
  std::size_t moves_ = 0;
};

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
bool Interpreter::missingTool() const { return impl_->missing_tool; }

RunSummary Interpreter::run(const Program& program, MoveSink& target) {
  Impl& s = *impl_;
  MoveBudget sink(target, s.options.max_moves);
  s.summary = RunSummary{};
  s.reported_tool = -1;
  s.missing_tool = false;
  s.report_blocks = sink.wantsBlocks();
  const Impl::Outcome outcome = s.runProgram(program, 0, sink, false);
  try {
    s.flushCompensation(sink);  // M2 flushed already; a program ending otherwise does it here
  } catch (const GcodeError& e) {
    throw IoError(locate(program.file(), program.lineCount(), e.what()));
  }
  if (outcome == Impl::Outcome::kEnded) {
    s.summary.ended_by_m2 = true;
    return s.summary;
  }
  if (s.options.require_program_end && !program.closedByPercent())
    throw IoError(locate(program.file(), program.lineCount(), kNoProgramEnd));
  return s.summary;
}

Interpreter::Impl::Outcome Interpreter::Impl::runProgram(const Program& program,
                                                         std::size_t pc,
                                                         MoveSink& sink,
                                                         bool external) {
  const std::vector<Block>& blocks = program.blocks();
  ProgramFlow flow(program, options, params, *this, external);
  std::size_t line = 0;
  try {
    while (pc < blocks.size()) {
      const Block& b = blocks[pc];
      line = b.line;
      ++summary.blocks;
      if (b.block_delete && options.block_delete) {
        ++pc;
        continue;
      }
      block_index = external ? kNoBlock : pc;  // a sub file's blocks are not the program's
      if (b.o_kind == OKind::kNone) {
        if (!execute(b, sink)) return Outcome::kEnded;
        if (fanuc.kind == 0) {
          ++pc;
          continue;
        }
        const FanucRequest request = std::exchange(fanuc, FanucRequest{});
        pc = flow.fanuc(request, pc);
        if (pc == kNoBlock) return Outcome::kEnded;  // M99 in the main program
        continue;
      }
      if (report_blocks) {
        evaluated.clear();
        sink.onBlock(b, block_index, evaluated);
      }
      const std::size_t next = flow.step(pc);
      if (next == kReturnToCaller) return Outcome::kReturned;
      if (next == kExternalCall) {
        if (callExternal(b.line, flow.external().name, flow.external().args, sink) ==
            Outcome::kEnded)
          return Outcome::kEnded;
        ++pc;
        continue;
      }
      pc = next;
    }
  } catch (const GcodeError& e) {
    throw IoError(locate(program.file(), line, e.what()));
  }
  return Outcome::kFellOff;
}

RunSummary Interpreter::runStream(LineReader& reader, MoveSink& target) {
  Impl& s = *impl_;
  MoveBudget sink(target, s.options.max_moves);
  s.summary = RunSummary{};
  s.missing_tool = false;
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
        reader.setLenient(true);  // LinuxCNC reads nothing after M2: the rest is not checked
        while (reader.next(b)) {
        }
        return s.summary;
      }
      if (std::exchange(s.fanuc, FanucRequest{}).kind != 0)
        throw GcodeError("M98/M99 need the whole program (read it with Program::parse)");
    } catch (const GcodeError& e) {
      throw IoError(locate(reader.file(), b.line, e.what()));
    }
  }
  try {
    s.flushCompensation(sink);
  } catch (const GcodeError& e) {
    throw IoError(locate(reader.file(), reader.lines(), e.what()));
  }
  if (s.options.require_program_end && !reader.closedByPercent())
    throw IoError(locate(reader.file(), reader.lines(), kNoProgramEnd));
  return s.summary;
}

}  // namespace pkm::cnc
