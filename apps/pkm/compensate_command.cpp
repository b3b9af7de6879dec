// `pkm compensate table`: controller compensation tables (LinuxCNC COMP_FILE type 0/1, SINUMERIK
// 840D EEC and CEC part programs, ISG CSV) from ISO 230-2 positioning or straightness files
// (docs/compensation.md).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "analyze_common.hpp"
#include "cli_common.hpp"
#include "pkm/compensation/axis_table.hpp"
#include "pkm/compensation/isg_comp.hpp"
#include "pkm/compensation/linuxcnc_comp.hpp"
#include "pkm/compensation/siemens_comp.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/io/positioning_files.hpp"
#include "pkm/metrology/iso230_2.hpp"
#include "pkm/metrology/straightness.hpp"

namespace pkm::cli {
namespace {

namespace fs = std::filesystem;
namespace comp = compensation;
using Json = nlohmann::ordered_json;

struct TableState {
  std::vector<std::string> data;
  std::string format;
  std::string axis, input_axis, output_axis;
  std::string out;
  std::string line = "endpoint";
  std::optional<std::size_t> max_points;
  int encoder = 0;
  int table_index = 0;
  bool force = false;
  bool json = false;
};

/// What was built, for the summary.
struct Built {
  std::string text;
  std::size_t input_rows = 0, rows = 0;
  double first = 0.0, last = 0.0;
  double max_correction = 0.0;  ///< largest |stored correction| (mm), as the controller applies it
  std::string axis;             ///< compensated axis
  std::optional<std::string> input_axis;
  std::optional<metrology::Iso230_2Result> iso;
};

void note(const std::string& text) { fmt::print(stderr, "pkm: note: {}\n", text); }

void noteResampled(std::size_t from, std::size_t to, bool even) {
  if (from == to && !even) return;
  note(fmt::format("resampled {} rows to {} evenly spaced rows (linear interpolation)", from, to));
}

/// The positioning table of the --data files, fitted to the format.
Built buildAxisTable(const TableState& st, comp::TableFormat format, std::size_t max_points) {
  if (st.axis.empty()) {
    throw InvalidArgument(fmt::format("--axis is required for --format {}", st.format));
  }
  const auto samples = io::readPositioningSamples(io::readNamedTexts(st.data));
  Built b;
  b.iso = metrology::evaluateIso230_2(samples);
  const comp::FormatTraits tr = comp::traits(format);
  const comp::AxisErrorTable raw = comp::tableFromIso230_2(*b.iso, st.axis);
  const comp::AxisErrorTable t = comp::fitToTarget(raw, tr, max_points);
  if (t.nominal != raw.nominal) noteResampled(raw.size(), t.size(), tr.even_spacing);
  if (!b.iso->bidirectional) {
    note("unidirectional data: the one direction's mean deviations are used for both directions");
  }
  b.input_rows = raw.size();
  b.rows = t.size();
  b.first = t.nominal.front();
  b.last = t.nominal.back();
  b.axis = t.axis;
  for (std::size_t i = 0; i < t.size(); ++i) {
    b.max_correction =
        tr.bidirectional
            ? std::max({b.max_correction, std::abs(t.error_up[i]), std::abs(t.error_down[i])})
            : std::max(b.max_correction, std::abs(t.meanError(i)));
  }
  switch (format) {
    case comp::TableFormat::kLinuxcnc0:
    case comp::TableFormat::kLinuxcnc1:
      b.text = comp::writeLinuxcncComp(
          comp::linuxcncCompFromTable(t, format == comp::TableFormat::kLinuxcnc0 ? 0 : 1));
      break;
    case comp::TableFormat::kSiemensEec:
      b.text = comp::writeSiemensEec(comp::siemensEecFromTable(t, st.encoder));
      break;
    case comp::TableFormat::kIsgCsv: {
      const std::vector<comp::IsgBlock> blocks{comp::isgBlockFromTable(t)};
      b.text = comp::writeIsgCsv(blocks);
      break;
    }
    case comp::TableFormat::kSiemensCec:
      break;
  }
  if (!tr.bidirectional && b.iso->bidirectional) {
    note(fmt::format(
        "{} has one table per axis: wrote the mean of both directions; the reversal (B = {:.6g} "
        "mm) is left to the control's backlash compensation",
        st.format,
        b.iso->B));
  }
  return b;
}

/// The straightness table of the --data files (line removed as --line), fitted to the format.
Built buildCrossTable(const TableState& st, comp::TableFormat format, std::size_t max_points) {
  if (st.input_axis.empty() || st.output_axis.empty()) {
    throw InvalidArgument(fmt::format(
        "--format {} with straightness data needs --input-axis and --output-axis", st.format));
  }
  const io::Profile p = io::readStraightness(io::readNamedTexts(st.data));
  comp::CrossAxisTable raw =
      comp::crossTableFromPoints(st.input_axis, st.output_axis, p.position, p.value);
  if (st.line != "raw") {
    const metrology::ReferenceLine line = st.line == "lsq"
                                              ? metrology::leastSquaresLine(raw.position, raw.error)
                                              : metrology::endpointLine(raw.position, raw.error);
    for (std::size_t i = 0; i < raw.position.size(); ++i) raw.error[i] -= line.at(raw.position[i]);
  }
  const comp::FormatTraits tr = comp::traits(format);
  const comp::CrossAxisTable t = comp::fitToTarget(raw, tr, max_points);
  if (t.position != raw.position) noteResampled(raw.position.size(), t.position.size(), true);
  Built b;
  b.input_rows = raw.position.size();
  b.rows = t.position.size();
  b.first = t.position.front();
  b.last = t.position.back();
  b.axis = t.output_axis;
  b.input_axis = t.input_axis;
  for (double e : t.error) b.max_correction = std::max(b.max_correction, std::abs(e));
  if (format == comp::TableFormat::kSiemensCec) {
    b.text = comp::writeSiemensCec(comp::siemensCecFromTable(t, st.table_index));
  } else {
    const std::vector<comp::IsgBlock> blocks{comp::isgBlockFromTable(t)};
    b.text = comp::writeIsgCsv(blocks);
  }
  return b;
}

void writeOutput(const TableState& st, const std::string& text) {
  std::error_code ec;
  if (!st.force && fs::exists(st.out, ec)) {
    throw IoError(fmt::format("{}: exists; refusing to overwrite (use --force)", st.out));
  }
  std::ofstream f(st.out, std::ios::binary | std::ios::trunc);
  if (!f) throw IoError(fmt::format("{}: cannot open for writing", st.out));
  f << text;
  f.close();
  if (!f) throw IoError(fmt::format("{}: write failed", st.out));
}

void runTable(const TableState& st) {
  const comp::TableFormat format = comp::parseTableFormat(st.format);
  const comp::FormatTraits tr = comp::traits(format);
  const std::size_t max_points = st.max_points.value_or(tr.default_max_points);
  const bool cross = format == comp::TableFormat::kSiemensCec ||
                     (format == comp::TableFormat::kIsgCsv && !st.output_axis.empty());
  const Built b =
      cross ? buildCrossTable(st, format, max_points) : buildAxisTable(st, format, max_points);
  writeOutput(st, b.text);
  if (st.json) {
    Json j{{"format", st.format},
           {"out", st.out},
           {"axis", b.axis},
           {"rows", b.rows},
           {"input_rows", b.input_rows},
           {"first", b.first},
           {"last", b.last},
           {"max_correction", b.max_correction}};
    if (b.input_axis) j["input_axis"] = *b.input_axis;
    if (b.iso) {
      j["E"] = b.iso->E;
      j["B"] = b.iso->B;
      j["M"] = b.iso->M;
    }
    printJson(j);
    return;
  }
  Output out;
  out.text() += fmt::format("compensation table ({}, axis {}{})\n",
                            st.format,
                            b.axis,
                            b.input_axis ? fmt::format(" over {}", *b.input_axis) : "");
  out.text() += fmt::format("rows\t{}\nrange\t{:.6g}\t{:.6g}\nmax_correction\t{:.6g} mm\n",
                            b.rows,
                            b.first,
                            b.last,
                            b.max_correction);
  if (b.iso && std::isfinite(b.iso->E)) {
    out.text() += fmt::format("measured E\t{:.6g} mm\n", b.iso->E);
  }
  out.text() += fmt::format("wrote\t{}\n", st.out);
}

void addCompensateCommand(CLI::App& app) {
  CLI::App* compensate = app.add_subcommand(
      "compensate", "controller compensation tables from measurements (docs/compensation.md)");
  compensate->require_subcommand(1);
  auto st = std::make_shared<TableState>();
  CLI::App* cmd = compensate->add_subcommand(
      "table",
      "write an axis error table for a controller from ISO 230-2 positioning files (or "
      "straightness files for siemens-cec / isg with --output-axis)");
  cmd->add_option("--data", st->data, "measurement file(s): as pkm analyze iso230-2 / straightness")
      ->required()
      ->expected(1, CLI::detail::expected_max_vector_size)
      ->check(CLI::ExistingFile);
  cmd->add_option("--format", st->format, "linuxcnc0, linuxcnc1, siemens-eec, siemens-cec or isg")
      ->required()
      ->check(CLI::IsMember({"linuxcnc0", "linuxcnc1", "siemens-eec", "siemens-cec", "isg"}));
  cmd->add_option("--axis", st->axis, "axis name as the controller knows it (X, X1, AX1, ...)");
  cmd->add_option("--input-axis", st->input_axis, "straightness: the base axis (argument)");
  cmd->add_option("--output-axis", st->output_axis, "straightness: the compensated axis");
  cmd->add_option("--line",
                  st->line,
                  "straightness: reference line removed first: endpoint (default), lsq or raw")
      ->check(CLI::IsMember({"endpoint", "lsq", "raw"}));
  cmd->add_option("--out,-o", st->out, "output file")->required();
  cmd->add_flag("--force", st->force, "overwrite an existing output file");
  cmd->add_option("--max-points",
                  st->max_points,
                  "most rows (default: linuxcnc 256, siemens 200, isg 1500); longer tables are "
                  "resampled evenly")
      ->check(CLI::Range(2, 1'000'000));
  cmd->add_option("--encoder", st->encoder, "siemens-eec: measuring system 0 or 1")
      ->check(CLI::IsMember({0, 1}));
  cmd->add_option("--table", st->table_index, "siemens-cec: table index t (default 0)")
      ->check(CLI::Range(0, 1000));
  cmd->add_flag("--json", st->json, "print one JSON object instead of the summary");
  cmd->callback([st] { runTable(*st); });
}

const CommandRegistration kRegisterCompensate{50, &addCompensateCommand};

}  // namespace
}  // namespace pkm::cli
