// libFuzzer harness for the G-code reader and interpreter: any input must either run or throw
// pkm::IoError / pkm::InvalidArgument; never crash, hang (loops are capped), or trip a sanitizer.
// Build and run: fuzz/run.sh (clang++-14 -fsanitize=fuzzer,address,undefined).
#include <cstddef>
#include <cstdint>
#include <string_view>

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
  options.tools.tools[1] = pkm::cnc::ToolEntry{1, 1, {0, 0, 10, 0, 0, 0}, 3};
  return options;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  // The whole-program path, and the streaming path `pkm gcode moves` takes without O-words.
  try {
    const pkm::cnc::Program program = pkm::cnc::Program::parse(text, "fuzz.ngc");
    pkm::cnc::Interpreter interp(fuzzOptions());
    NullSink sink;
    interp.run(program, sink);
  } catch (const pkm::IoError&) {
  } catch (const pkm::InvalidArgument&) {
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
