// `pkm hexapod fk` as a workflow: the read-solve-print pipeline (workflow/hexapod_fk_file.hpp).
#include "pkm/workflow/hexapod_fk_file.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <charconv>
#include <exception>
#include <future>
#include <memory>
#include <mutex>
#include <semaphore>
#include <span>
#include <utility>
#include <vector>

#include "pkm/core/units.hpp"
#include "pkm/io/csv.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/workflow/kinematics_path.hpp"
#include "serial_worker.hpp"
#include "thread_placement.hpp"
#include "vector_pool.hpp"

namespace pkm::workflow {
namespace {

namespace kin = pkm::kinematics;

const std::vector<std::string> kFkLengthColumns = {"l0", "l1", "l2", "l3", "l4", "l5"};

/// Room for one output row: at most six numbers of kMaxNumberChars, an iteration count of 11, a
/// status of 14 and 8 separators.
constexpr std::size_t kFkRowRoom = 8 * io::kMaxNumberChars;
/// Rows solved between two hand-overs to the printing thread, and the largest input chunk (the
/// first chunks are smaller, so that solving starts early).
constexpr std::size_t kFkPiece = 1024;
constexpr std::size_t kFkMaxChunk = 8192;
/// Solved pieces waiting for the printing thread at most (the memory stays bounded when printing
/// is the slower side).
constexpr std::ptrdiff_t kFkPiecesQueued = 16;
/// Pieces waiting for the printing thread from which on the solving thread converts the angles.
constexpr int kFkBehind = 2;

/// Writes the rows' CSV text at `o` (room: kFkRowRoom a row) and returns its end; their angles
/// come from `angles`, which must see every step in order.
char* formatFkRows(std::span<const FkStep> rows, HexapodFkAngles& angles, char* o) {
  for (const FkStep& r : rows) {
    const Eigen::Vector3d rpy = angles.next(r);
    if (r.summary.ok()) {
      for (int i = 0; i < 6; ++i) {
        o = io::writeNumber(o, i < 3 ? r.pose.position[i] : radToDeg(rpy[i - 3]));
        *o++ = ',';
      }
    } else {
      o = std::copy_n(",,,,,,", 6, o);  // no pose on failure: never print a wrong one
    }
    o = std::to_chars(o, o + io::kMaxNumberChars, r.summary.iterations).ptr;
    *o++ = ',';
    const std::string_view status = kin::toString(r.summary.status);
    o = std::copy(status.begin(), status.end(), o);
    *o++ = '\n';
  }
  return o;
}

/// Rows of strut readings read in one go, and what ended the reading: the end of the input or an
/// error (a bad line), which is raised after the rows before it are printed.
struct FkInputChunk {
  std::vector<kin::StrutVector> readings;
  bool last = false;
  std::exception_ptr error;
};

FkInputChunk readFkChunk(io::CsvReader& reader,
                         std::size_t rows,
                         std::vector<kin::StrutVector>&& storage) {
  FkInputChunk chunk;
  chunk.readings = std::move(storage);
  chunk.readings.reserve(rows);
  std::array<double, 6> row{};
  try {
    while (chunk.readings.size() < rows) {
      if (!reader.next(row)) {
        chunk.last = true;
        break;
      }
      chunk.readings.emplace_back(row.data());
    }
  } catch (...) {
    chunk.error = std::current_exception();
    chunk.last = true;
  }
  return chunk;
}

/// The pipeline's shared state: the second thread's output buffer, the pools, the bound on
/// waiting pieces.
struct FkPipeline {
  explicit FkPipeline(const io::HexapodMachine& machine, const HexapodFkFileRequest& r)
      : angles(machine, r.seed, r.from_seed), reader(r.lengths, kFkLengthColumns) {}
  HexapodFkAngles angles;
  io::CsvReader reader;
  std::unique_ptr<char[]> text = std::make_unique_for_overwrite<char[]>(kFkPiece * kFkRowRoom);
  std::counting_semaphore<kFkPiecesQueued> room{kFkPiecesQueued};
  std::atomic<int> queued{0};  // pieces posted and not yet printed
  detail::VectorPool<kin::StrutVector> chunk_pool;
  detail::VectorPool<FkStep> piece_pool;
  detail::SerialWorker printer;  // last: its jobs use the above

  /// The next `rows` readings, read on the second thread.
  std::future<FkInputChunk> readAhead(std::size_t rows) {
    auto next = std::make_shared<std::promise<FkInputChunk>>();
    std::future<FkInputChunk> result = next->get_future();
    printer.post(
        [this, next, rows] { next->set_value(readFkChunk(reader, rows, chunk_pool.take())); });
    return result;
  }
};

}  // namespace

HexapodFkFileSummary solveHexapodFkFile(const io::HexapodMachine& machine,
                                        const HexapodFkFileRequest& request,
                                        const std::function<void(std::string_view)>& write) {
  // The path solves; the angles are converted with the text, on the other thread.
  HexapodFkPath path(machine, request.seed, request.from_seed, /*angles=*/false);
  FkPipeline p(machine, request);
  write(kHexapodFkHeader);
  // Rows are solved in order on this thread (each seeds the next, as in a servo loop). The
  // second thread reads the input a chunk ahead and prints the solved rows a piece at a time, in
  // order (the angles and the reader see their rows in order); `write` is its alone from here.
  // Printing (angles, shortest round-trip text, the writes) may cost more than solving, on long
  // numbers: then this thread converts the rotations to angles too, and at most kFkPiecesQueued
  // pieces wait, so that the memory stays bounded.
  const detail::PipelinePlacement placement(p.printer.thread());  // each on its own CPU
  HexapodFkFileSummary summary;
  std::size_t chunk_rows = kFkPiece;
  FkInputChunk chunk = p.readAhead(chunk_rows).get();
  while (true) {
    std::future<FkInputChunk> next;
    if (!chunk.last) next = p.readAhead(chunk_rows = std::min(2 * chunk_rows, kFkMaxChunk));
    for (std::size_t first = 0; first < chunk.readings.size(); first += kFkPiece) {
      auto piece = std::make_shared<std::vector<FkStep>>(p.piece_pool.take());
      const std::size_t end = std::min(first + kFkPiece, chunk.readings.size());
      piece->reserve(end - first);
      for (std::size_t i = first; i < end; ++i) {
        path.solve(chunk.readings[i], piece->emplace_back());
        summary.failed += piece->back().summary.ok() ? 0 : 1;
      }
      summary.rows += end - first;
      // When the printing thread falls behind, this one takes the angles' costly share.
      if (p.queued.load(std::memory_order_relaxed) >= kFkBehind)
        for (FkStep& step : *piece) HexapodFkAngles::convert(step);
      p.queued.fetch_add(1, std::memory_order_relaxed);
      p.room.acquire();
      // The piece's room is given back when its job is done with, run or dropped (after a failed
      // `write` the worker drops the jobs queued behind it): this thread never waits for good.
      std::shared_ptr<void> permit(nullptr, [&p](void*) {
        p.queued.fetch_sub(1, std::memory_order_relaxed);
        p.room.release();
      });
      p.printer.post([piece, &p, &write, permit = std::move(permit)] {
        write({p.text.get(), formatFkRows(*piece, p.angles, p.text.get())});
        p.piece_pool.giveBack(std::move(*piece));
      });
    }
    if (chunk.last || p.printer.failed()) {
      p.printer.drain();  // rethrows a failed `write`
      if (chunk.error) std::rethrow_exception(chunk.error);
      return summary;
    }
    p.chunk_pool.giveBack(std::move(chunk.readings));
    try {
      chunk = next.get();
    } catch (const std::future_error&) {  // the read was dropped after a failed `write`
      p.printer.drain();
      throw;
    }
  }
}

}  // namespace pkm::workflow
