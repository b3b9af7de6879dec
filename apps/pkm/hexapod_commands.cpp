// `pkm hexapod ...`: ik, fk, check, describe, hal, linuxcnc-params, machines (docs/formats.md).
#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <charconv>
#include <cmath>
#include <exception>
#include <future>
#include <memory>
#include <mutex>
#include <optional>
#include <semaphore>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "cli_common.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/csv.hpp"
#include "pkm/io/kinematics_csv.hpp"
#include "pkm/io/linuxcnc_hal.hpp"
#include "pkm/io/linuxcnc_hexapod_params.hpp"
#include "pkm/io/machine_description.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/kinematics/hexapod_checks.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "pkm/workflow/kinematics_path.hpp"
#include "serial_worker.hpp"
#include "thread_placement.hpp"

namespace pkm::cli {

namespace kin = pkm::kinematics;

namespace {

const std::vector<std::string> kPoseColumns = {"x", "y", "z", "a", "b", "c"};
const std::vector<std::string> kLengthColumns = {"l0", "l1", "l2", "l3", "l4", "l5"};

kin::PoseRpy poseFromRow(const std::array<double, 6>& v) {
  kin::PoseRpy p;
  p.position = {v[0], v[1], v[2]};
  p.rpy = {degToRad(v[3]), degToRad(v[4]), degToRad(v[5])};
  return p;
}

kin::PoseRpy parseSeed(const std::string& text) {
  std::array<double, 6> v{};
  std::size_t pos = 0;
  for (std::size_t i = 0; i < 6; ++i) {
    const std::size_t comma = text.find(',', pos);
    if ((comma == std::string::npos) != (i == 5) ||
        !io::parseFiniteDouble(
            std::string_view(text).substr(
                pos, comma == std::string::npos ? std::string::npos : comma - pos),
            v[i]))
      throw IoError(fmt::format("--seed '{}': expected six finite numbers x,y,z,a,b,c", text));
    pos = comma + 1;
  }
  return poseFromRow(v);
}

void runIk(const MachineOption& machine_opt, const std::string& poses) {
  const io::HexapodMachine machine = machine_opt.load();
  kin::HexapodData data(machine.model);
  io::CsvReader reader(poses, kPoseColumns);
  Output out;
  out.text() += "l0,l1,l2,l3,l4,l5,status\n";
  std::array<double, 6> row{};
  while (reader.next(row)) {
    const kin::HexapodCheckResult check = kin::checkPose(machine.model, data, poseFromRow(row));
    for (int i = 0; i < kin::kStruts; ++i) {
      io::appendNumber(out.text(), check.readings[i]);
      out.text() += ',';
    }
    out.text() += check.status();
    out.text() += '\n';
    out.maybeFlush();
  }
}

/// Writes the rows' CSV text at `o` (room: kFkRowRoom a row) and returns its end; their angles come
/// from `angles`, which must see every step in order.
/// At most six numbers of kMaxNumberChars, an iteration count of 11, a status of 14 and 8
/// separators a row.
constexpr std::size_t kFkRowRoom = 8 * io::kMaxNumberChars;
char* formatFkRows(const workflow::FkStep* rows,
                   std::size_t count,
                   workflow::HexapodFkAngles& angles,
                   char* o) {
  for (const workflow::FkStep& r : std::span(rows, count)) {
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

/// Vectors handed between the threads and back for reuse: fresh memory for every piece and chunk
/// would cost a page fault per 4 KiB. Thread-safe.
template <typename T>
class VectorPool {
 public:
  /// An empty vector, with the capacity of one given back earlier if there is one.
  std::vector<T> take() {
    const std::lock_guard lock(mutex_);
    if (free_.empty()) return {};
    std::vector<T> v = std::move(free_.back());
    free_.pop_back();
    return v;
  }
  /// Keeps `v` for a later take() (or frees it, when even that fails: does not throw).
  void giveBack(std::vector<T>&& v) noexcept {
    v.clear();
    try {
      const std::lock_guard lock(mutex_);
      free_.push_back(std::move(v));
    } catch (...) {  // out of memory or a failed lock: v is freed instead of kept
    }
  }

 private:
  std::mutex mutex_;
  std::vector<std::vector<T>> free_;
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

/// Rows solved between two hand-overs to the printing thread, and the largest input chunk (the
/// first chunks are smaller, so that solving starts early).
constexpr std::size_t kFkPiece = 1024;
constexpr std::size_t kFkMaxChunk = 8192;
/// Solved pieces waiting for the printing thread at most (the memory stays bounded when printing
/// is the slower side).
constexpr std::ptrdiff_t kFkPiecesQueued = 16;
/// Pieces waiting for the printing thread from which on this thread converts the angles.
constexpr int kFkBehind = 2;

void runFk(const MachineOption& machine_opt,
           const std::string& lengths,
           const std::string& seed_text,
           bool from_seed) {
  const io::HexapodMachine machine = machine_opt.load();
  const std::optional<kin::PoseRpy> seed =
      seed_text.empty() ? std::nullopt : std::optional(parseSeed(seed_text));
  // The path solves; the angles are converted with the text, on the other thread.
  workflow::HexapodFkPath path(machine, seed, from_seed, /*angles=*/false);
  workflow::HexapodFkAngles angles(machine, seed, from_seed);
  io::CsvReader reader(lengths, kLengthColumns);
  Output out;
  out.text() += "x,y,z,a,b,c,iterations,status\n";
  // Rows are solved in order on this thread (each seeds the next, as in a servo loop). A second
  // thread reads the input a chunk ahead and prints the solved rows a piece at a time, in order
  // (the angles and the reader see their rows in order); `out` is its alone from here. Printing
  // (angles, shortest round-trip text, the writes) may cost more than solving, on long numbers:
  // then this thread converts the rotations to angles too, and at most kFkPiecesQueued pieces
  // wait, so that the memory stays bounded.
  auto text = std::make_unique_for_overwrite<char[]>(kFkPiece * kFkRowRoom);
  std::counting_semaphore<kFkPiecesQueued> room(kFkPiecesQueued);
  std::atomic<int> queued{0};  // pieces posted and not yet printed
  VectorPool<kin::StrutVector> chunk_pool;
  VectorPool<workflow::FkStep> piece_pool;
  SerialWorker printer;                    // last: its jobs use the above
  placePipelineThreads(printer.thread());  // each of the two on its own CPU
  auto read_ahead = [&printer, &reader, &chunk_pool](std::size_t rows) {
    auto next = std::make_shared<std::promise<FkInputChunk>>();
    std::future<FkInputChunk> result = next->get_future();
    printer.post([next, &reader, &chunk_pool, rows] {
      next->set_value(readFkChunk(reader, rows, chunk_pool.take()));
    });
    return result;
  };
  std::size_t chunk_rows = kFkPiece;
  FkInputChunk chunk = read_ahead(chunk_rows).get();
  while (true) {
    std::future<FkInputChunk> next;
    if (!chunk.last) {
      chunk_rows = std::min(2 * chunk_rows, kFkMaxChunk);
      next = read_ahead(chunk_rows);
    }
    for (std::size_t first = 0; first < chunk.readings.size(); first += kFkPiece) {
      auto piece = std::make_shared<std::vector<workflow::FkStep>>(piece_pool.take());
      const std::size_t end = std::min(first + kFkPiece, chunk.readings.size());
      piece->reserve(end - first);
      for (std::size_t i = first; i < end; ++i)
        path.solve(chunk.readings[i], piece->emplace_back());
      // When the printing thread falls behind, this one takes the angles' costly share.
      if (queued.load(std::memory_order_relaxed) >= kFkBehind)
        for (workflow::FkStep& step : *piece) workflow::HexapodFkAngles::convert(step);
      queued.fetch_add(1, std::memory_order_relaxed);
      room.acquire();
      printer.post([piece, &angles, &out, &room, &queued, &piece_pool, buffer = text.get()] {
        out.write({buffer, formatFkRows(piece->data(), piece->size(), angles, buffer)});
        piece_pool.giveBack(std::move(*piece));
        queued.fetch_sub(1, std::memory_order_relaxed);
        room.release();  // nothing above throws
      });
    }
    if (chunk.last) {
      printer.drain();
      out.flush();
      if (chunk.error) std::rethrow_exception(chunk.error);
      return;
    }
    chunk_pool.giveBack(std::move(chunk.readings));
    chunk = next.get();
  }
}

void runCheck(const MachineOption& machine_opt, const std::string& poses) {
  const io::HexapodMachine machine = machine_opt.load();
  kin::HexapodData data(machine.model);
  io::CsvReader reader(poses, kPoseColumns);
  Output out;
  out.text() += io::hexapodCheckCsvHeader();
  std::array<double, 6> row{};
  std::size_t index = 0;
  while (reader.next(row)) {
    io::appendHexapodCheckRow(
        out.text(), index++, kin::checkPose(machine.model, data, poseFromRow(row)));
    out.maybeFlush();
  }
}

/// The options of `pkm hexapod`'s subcommands, shared by their callbacks.
struct HexapodCliState {
  MachineOption machine;
  std::string poses, lengths, seed;
  bool json = false;
  std::string kins = "genhexkins";
  bool from_seed = false;
};

/// Adds `pkm hexapod ik`, `fk` and `check` to `hex`.
void addHexapodSolveCommands(CLI::App* hex, const std::shared_ptr<HexapodCliState>& st) {
  CLI::App* ik = hex->add_subcommand(
      "ik", "inverse kinematics: poses x,y,z,a,b,c -> strut readings l0..l5,status");
  st->machine.add(*ik);
  ik->add_option("--poses,-p",
                 st->poses,
                 "CSV with header x,y,z,a,b,c (lengths in the machine unit, degrees); - = stdin")
      ->required();
  ik->callback([st] { runIk(st->machine, st->poses); });

  CLI::App* fk = hex->add_subcommand(
      "fk", "forward kinematics: strut readings l0..l5 -> x,y,z,a,b,c,iterations,status");
  st->machine.add(*fk);
  fk->add_option("--lengths,-l", st->lengths, "CSV with header l0,...,l5 (machine unit); - = stdin")
      ->required();
  fk->add_option(
      "--seed",
      st->seed,
      "first row's seed pose x,y,z,a,b,c (default: home); later rows use the previous solution");
  fk->add_flag("--from-seed",
               st->from_seed,
               "solve every row on its own from the seed (rows that are not a path)");
  fk->callback([st] { runFk(st->machine, st->lengths, st->seed, st->from_seed); });

  CLI::App* check = hex->add_subcommand(
      "check", "per pose: stroke, joint angles, leg interference, conditioning");
  st->machine.add(*check);
  check->add_option("--poses,-p", st->poses, "CSV with header x,y,z,a,b,c; - = stdin")->required();
  check->callback([st] { runCheck(st->machine, st->poses); });
}

/// Adds `pkm hexapod describe`, `hal`, `linuxcnc-params` and `machines` to `hex`.
void addHexapodMachineCommands(CLI::App* hex, const std::shared_ptr<HexapodCliState>& st) {
  CLI::App* describe =
      hex->add_subcommand("describe", "print the machine; --json writes it as a pkm machine file");
  st->machine.add(*describe);
  describe->add_flag("--json", st->json, "write the machine as JSON (docs/machine-format.md)");
  describe->callback([st] {
    const io::HexapodMachine m = st->machine.load();
    Output out;
    if (st->json)
      out.text() += io::writeHexapodJson(m);
    else
      out.text() += io::describeHexapodMachine(m);
  });

  CLI::App* hal = hex->add_subcommand(
      "hal", "write the machine as a LinuxCNC setp block (genhexkins, or pkm's pkmhexkins)");
  st->machine.add(*hal);
  hal->add_option("--kins",
                  st->kins,
                  "kinematics module: genhexkins (LinuxCNC's; joints are joint-centre distances) "
                  "or pkmhexkins (pkm's; joints are the strut readings, all 42 parameters)")
      ->check(CLI::IsMember({"genhexkins", "pkmhexkins"}))
      ->capture_default_str();
  hal->callback([st] {
    Output out;
    const io::HexapodMachine m = st->machine.load();
    out.text() += st->kins == "pkmhexkins" ? io::writePkmhexkinsSetp(m) : io::writeLinuxcncSetp(m);
  });

  CLI::App* params = hex->add_subcommand(
      "linuxcnc-params",
      "write the parameter file of the LinuxCNC kinematics pkmhexkins (loadrt pkmhexkins "
      "params=FILE: read and checked at load)");
  st->machine.add(*params);
  params->callback([st] {
    Output out;
    out.text() += io::linuxcncHexapodParameters(st->machine.load());
  });

  CLI::App* list = hex->add_subcommand("machines", "list the built-in machines");
  list->callback([] {
    for (const auto& n : io::builtinMachineNames()) fmt::print("{}\n", n);
  });
}

}  // namespace

void addHexapodCommands(CLI::App& app) {
  CLI::App* hex = app.add_subcommand("hexapod", "hexapod (6-UPS Stewart platform) kinematics");
  hex->require_subcommand(1);
  auto st = std::make_shared<HexapodCliState>();
  addHexapodSolveCommands(hex, st);
  addHexapodMachineCommands(hex, st);
}

}  // namespace pkm::cli
