// `pkm gcode moves` as a workflow (workflow/gcode_moves.hpp).
#include "pkm/workflow/gcode_moves.hpp"

#include <fmt/format.h>

#include <cstring>
#include <memory>
#include <optional>
#include <semaphore>
#include <string_view>
#include <utility>
#include <vector>

#include "gcode_progress.hpp"
#include "pkm/cnc/interpreter.hpp"
#include "pkm/cnc/line_reader.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
#include "serial_worker.hpp"
#include "thread_placement.hpp"
#include "vector_pool.hpp"

namespace pkm::workflow {

namespace {

/// Formats the CSV rows and hands them on in blocks of about 1 MiB, on a second thread: the
/// interpreter (this thread) passes its moves in batches, and the other formats and writes them
/// in order while the next batch is interpreted (formatting the numbers costs about as much as
/// interpreting the lines). At most kQueued batches wait, so that the memory stays bounded when
/// writing is the slower side. Only the second thread calls `write`.
class CsvSink final : public cnc::MoveSink {
 public:
  explicit CsvSink(TextOutput write)
      : write_(std::move(write)), buffer_(new char[kFlush + cnc::kMaxMoveCsvRow]) {
    const std::string_view header = cnc::kMoveCsvHeader;
    std::memcpy(buffer_.get(), header.data(), header.size());
    used_ = header.size();
    buffer_[used_++] = '\n';
    batch_.reserve(kBatch);
  }
  void onMove(const cnc::Move& m) override {
    batch_.push_back(m);
    if (batch_.size() == kBatch) post();
  }
  /// Formats and writes what is left, and waits for it; rethrows a failure of `write`.
  void finish() {
    post();
    worker_.post([this] { flush(); });
    worker_.drain();
  }

 private:
  static constexpr std::size_t kFlush = 1 << 20;
  static constexpr std::size_t kBatch = 2048;
  static constexpr std::ptrdiff_t kQueued = 8;

  void post() {
    if (batch_.empty()) return;
    if (worker_.failed()) worker_.drain();  // rethrows the failure of `write`
    room_.acquire();
    auto batch = std::make_shared<std::vector<cnc::Move>>(std::move(batch_));
    batch_ = pool_.take();
    batch_.reserve(kBatch);
    // The batch's room is given back when its job is done with, run or dropped.
    std::shared_ptr<void> permit(nullptr, [this](void*) { room_.release(); });
    worker_.post([this, batch, permit = std::move(permit)] {
      for (const cnc::Move& m : *batch) {
        used_ =
            static_cast<std::size_t>(cnc::writeMoveCsv(buffer_.get() + used_, m) - buffer_.get());
        if (used_ > kFlush) flush();
      }
      pool_.giveBack(std::move(*batch));
    });
  }
  void flush() {
    if (used_ > 0) write_(std::string_view(buffer_.get(), used_));
    used_ = 0;
  }

  TextOutput write_;
  std::unique_ptr<char[]> buffer_;  // kFlush + one row; the worker's alone
  std::size_t used_ = 0;
  std::vector<cnc::Move> batch_;
  std::counting_semaphore<kQueued> room_{kQueued};
  detail::VectorPool<cnc::Move> pool_;
  detail::SerialWorker worker_;                            // its jobs use the above
  detail::PipelinePlacement placement_{worker_.thread()};  // each thread on its own CPU
};

}  // namespace

void GcodeMovesRequest::validate() const {
  interpreter.validate();
  if (!out.empty()) io::checkOverwrite(out, force ? io::Overwrite::kAllow : io::Overwrite::kRefuse);
}

GcodeMovesResult runGcodeMoves(const GcodeMovesRequest& request,
                               const RunControl& control,
                               const TextOutput& output) {
  request.validate();
  cnc::Interpreter interpreter(request.interpreter.options());
  // A program without O-words is run while it is read (constant memory); one with O-words is
  // parsed whole first, so that its jumps resolve.
  const std::string& name = request.program.name;
  const std::string_view text =
      request.program_text.empty() ? std::string_view(request.program.text) : request.program_text;
  std::optional<cnc::Program> program;
  if (cnc::LineReader::mayHaveOWords(text)) program = cnc::Program::parse(text, name);
  cnc::LineReader reader(text, name);
  GcodeMovesResult result;
  std::optional<io::AtomicFile> file;  // an error leaves no partial file
  if (!request.out.empty()) file.emplace(request.out, io::Overwrite::kAllow);
  CsvSink sink([&](std::string_view text) {
    if (file)
      file->write(text);
    else if (output)
      output(text);
    else
      result.csv += text;
  });
  const detail::GcodeProgress progress(control);
  detail::ProgressMoveSink watched(sink, progress, 0, 0, name);
  const cnc::RunSummary s =
      program ? interpreter.run(*program, watched) : interpreter.runStream(reader, watched);
  sink.finish();
  if (file) file->commit();
  result.lines = program ? program->lineCount() : reader.lines();
  result.blocks = s.blocks;
  result.moves = s.moves;
  result.ended_by_m2 = s.ended_by_m2;
  result.note = fmt::format("{} lines, {} blocks executed, {} moves{}",
                            result.lines,
                            s.blocks,
                            s.moves,
                            s.ended_by_m2 ? "" : " (no M2/M30 at the end)");
  if (s.inch_moves > 0)
    result.note += fmt::format(
        "; {} of them programmed in inches (G20): the CSV is in mm and degrees, machine "
        "coordinates whatever G20/G21 says (divide x, y, z, cx, cy, cz and a linear feed by 25.4 "
        "for inches)",
        s.inch_moves);
  return result;
}

}  // namespace pkm::workflow
