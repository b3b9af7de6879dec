// libFuzzer harness for the G-code reader, interpreter and flattener: any input must either run or
// throw pkm::IoError / pkm::InvalidArgument; never crash, hang (loops are capped), or trip a
// sanitizer. A program that runs and flattens must give a flattened program that runs to the same
// number of motions (a trap otherwise).
// Build and run: fuzz/run.sh (clang++-14 -fsanitize=fuzzer,address,undefined).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "pkm/cnc/flatten.hpp"
#include "pkm/cnc/interpreter.hpp"
#include "pkm/core/error.hpp"

namespace {
class NullSink final : public pkm::cnc::MoveSink {
 public:
  void onMove(const pkm::cnc::Move& m) override { last = m.end[0]; }
  double last = 0.0;
};
}  // namespace

pkm::cnc::InterpreterOptions fuzzOptions() {
  pkm::cnc::InterpreterOptions options;
  options.max_loop_iterations = 2000;
  options.max_call_depth = 16;
  options.tools.tools[1] = pkm::cnc::ToolEntry{1, 1, {0, 0, 10, 0, 0, 0}, 3, ""};
  return options;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  // The whole-program path, and the streaming path `pkm gcode moves` takes without O-words.
  std::size_t moves = 0;
  bool ran = false;
  try {
    const pkm::cnc::Program program = pkm::cnc::Program::parse(text, "fuzz.ngc");
    pkm::cnc::Interpreter interp(fuzzOptions());
    NullSink sink;
    moves = interp.run(program, sink).moves;
    ran = true;
  } catch (const pkm::IoError&) {
  } catch (const pkm::InvalidArgument&) {
  }
  if (ran) {
    std::string flat;
    try {
      flat = pkm::cnc::flattenProgram(text, "fuzz.ngc", fuzzOptions()).text;
    } catch (const pkm::IoError&) {  // a block too long for a line, a non-finite value
      flat.clear();
    }
    if (!flat.empty()) {
      try {
        pkm::cnc::Interpreter again(fuzzOptions());
        NullSink sink;
        if (again.run(pkm::cnc::Program::parse(flat, "flat.ngc"), sink).moves != moves)
          __builtin_trap();
      } catch (const pkm::IoError&) {
        __builtin_trap();  // the flattened program of a program that runs must run
      }
    }
  }
  try {
    (void)pkm::cnc::LineReader::mayHaveOWords(text);
    pkm::cnc::LineReader reader(text, "fuzz.ngc");
    pkm::cnc::Interpreter interp(fuzzOptions());
    NullSink sink;
    interp.runStream(reader, sink);
  } catch (const pkm::IoError&) {
  } catch (const pkm::InvalidArgument&) {
  }
  return 0;
}
