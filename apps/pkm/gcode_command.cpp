// `pkm gcode moves PROGRAM`: interpret an RS274NGC program with LinuxCNC semantics and write one
// CSV row per motion in machine coordinates (docs/gcode.md).
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>

#include "cli_common.hpp"
#include "gcode_options.hpp"
#include "pkm/cnc/interpreter.hpp"
#include "pkm/cnc/line_reader.hpp"
#include "pkm/core/error.hpp"

namespace pkm::cli {

void addGcodeRunCommand(CLI::App& gcode);         // gcode_run.cpp
void addGcodeCompensateCommand(CLI::App& gcode);  // gcode_compensate.cpp
void addGcodeFlattenCommand(CLI::App& gcode);     // gcode_flatten.cpp

namespace {

struct MovesArgs {
  std::string program;
  std::string out;
  bool force = false;
  InterpreterArgs interpreter;
};

/// Streams rows into a buffer flushed to stdout or a file.
class CsvSink final : public cnc::MoveSink {
 public:
  explicit CsvSink(std::FILE* f) : file_(f) {
    buffer_.reserve(kFlush + 4096);
    buffer_ += cnc::kMoveCsvHeader;
    buffer_ += '\n';
  }
  void onMove(const cnc::Move& m) override {
    cnc::appendMoveCsv(buffer_, m);
    if (buffer_.size() > kFlush) flush();
  }
  void flush() {
    if (!buffer_.empty()) std::fwrite(buffer_.data(), 1, buffer_.size(), file_);
    buffer_.clear();
  }

 private:
  static constexpr std::size_t kFlush = 1 << 20;
  std::FILE* file_;
  std::string buffer_;
};

void runMoves(const MovesArgs& a) {
  cnc::InterpreterOptions options = a.interpreter.options();
  if (!a.out.empty() && !a.force && std::filesystem::exists(a.out))
    throw IoError(fmt::format("{} exists; pass --force to overwrite it", a.out));
  // A program without O-words is run while it is read (constant memory); one with O-words is
  // parsed whole first, so that its jumps resolve.
  const std::string text = cnc::Program::readFile(a.program);
  std::optional<cnc::Program> program;
  if (cnc::LineReader::mayHaveOWords(text)) program = cnc::Program::parse(text, a.program);
  cnc::LineReader reader(text, a.program);
  cnc::Interpreter interpreter(std::move(options));
  // Interpret into a temporary file first so that an error leaves no partial output file.
  std::FILE* f = stdout;
  std::string tmp;
  if (!a.out.empty()) {
    tmp = a.out + ".tmp";
    f = std::fopen(tmp.c_str(), "wb");
    if (f == nullptr) throw IoError(fmt::format("{}: cannot write", a.out));
  }
  try {
    CsvSink sink(f);
    const cnc::RunSummary s =
        program ? interpreter.run(*program, sink) : interpreter.runStream(reader, sink);
    sink.flush();
    fmt::print(stderr,
               "pkm: note: {} lines, {} blocks executed, {} moves{}\n",
               program ? program->lineCount() : reader.lines(),
               s.blocks,
               s.moves,
               s.ended_by_m2 ? "" : " (no M2/M30 at the end)");
  } catch (...) {
    if (f != stdout) {
      std::fclose(f);
      std::filesystem::remove(tmp);
    }
    throw;
  }
  if (f != stdout) {
    if (std::fclose(f) != 0) throw IoError(fmt::format("{}: write failed", a.out));
    std::filesystem::rename(tmp, a.out);
  } else {
    std::fflush(stdout);
  }
}

void addGcodeCommand(CLI::App& app) {
  CLI::App* g = app.add_subcommand("gcode", "RS274NGC (LinuxCNC) G-code programs");
  g->require_subcommand(1);
  auto a = std::make_shared<MovesArgs>();
  CLI::App* m = g->add_subcommand(
      "moves",
      "interpret PROGRAM and write one CSV row per motion in machine coordinates (mm, deg)");
  m->add_option("program", a->program, "G-code file (.ngc)")->required();
  m->add_option("--out", a->out, "write the CSV to FILE instead of standard output");
  m->add_flag("--force", a->force, "overwrite an existing --out file");
  a->interpreter.add(*m);
  m->callback([a] { runMoves(*a); });
  addGcodeRunCommand(*g);
  addGcodeCompensateCommand(*g);
  addGcodeFlattenCommand(*g);
}

const CommandRegistration kRegisterGcode{60, &addGcodeCommand};

}  // namespace
}  // namespace pkm::cli
