// `pkm compensate table` (compensation_table.hpp): ISO 230-2 or straightness data to a controller
// table.
#include "pkm/workflow/compensation_table.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "pkm/compensation/axis_table.hpp"
#include "pkm/compensation/isg_comp.hpp"
#include "pkm/compensation/linuxcnc_comp.hpp"
#include "pkm/compensation/siemens_comp.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/positioning_files.hpp"
#include "pkm/metrology/iso230_2.hpp"
#include "pkm/metrology/iso230_2_conformity.hpp"
#include "pkm/metrology/straightness.hpp"
#include "pkm/workflow/machine_unit.hpp"

namespace pkm::workflow {
namespace {

namespace comp = pkm::compensation;

/// A table built for the request: its text and summary.
struct Built {
  std::string text;
  io::CompensationTableSummary summary;
};

void noteResampled(const RunControl& control, std::size_t from, std::size_t to, bool even) {
  if (from == to && !even) return;
  if (control.notice)
    control.notice(
        fmt::format("resampled {} rows to {} evenly spaced rows (linear interpolation)", from, to));
}

std::string axisTableText(const comp::AxisErrorTable& t,
                          comp::TableFormat format,
                          const CompensationTableRequest& request) {
  switch (format) {
    case comp::TableFormat::kLinuxcnc0:
    case comp::TableFormat::kLinuxcnc1:
      return comp::writeLinuxcncComp(
          comp::linuxcncCompFromTable(t, format == comp::TableFormat::kLinuxcnc0 ? 0 : 1));
    case comp::TableFormat::kSiemensEec:
      return comp::writeSiemensEec(comp::siemensEecFromTable(t, request.encoder));
    case comp::TableFormat::kIsgCsv:
      return comp::writeIsgCsv(std::vector<comp::IsgBlock>{comp::isgBlockFromTable(t)});
    case comp::TableFormat::kSiemensCec:
      break;
  }
  return {};
}

/// The name of the table's unit ("mm" without a machine).
std::string unitName(const std::optional<MachineUnit>& unit) {
  return std::string(toString(unit ? unit->unit : LengthUnit::kMillimetre));
}

/// `table` (mm) in the machine's unit: every length divided by `per` (mm per machine unit).
comp::AxisErrorTable inUnit(comp::AxisErrorTable table, double per) {
  for (auto* column : {&table.nominal, &table.error_up, &table.error_down})
    for (double& v : *column) v /= per;
  return table;
}

/// The positioning table of the data, fitted to the format, in the machine's unit.
Built buildAxisTable(const CompensationTableRequest& request,
                     comp::TableFormat format,
                     std::size_t max_points,
                     const std::optional<MachineUnit>& unit,
                     const RunControl& control) {
  std::vector<std::string> unstated;
  const std::vector<metrology::PositioningSample> samples =
      io::readPositioningSamples(request.data, request.columns, &unstated);
  const metrology::Iso230_2Result iso = metrology::evaluateIso230_2(samples);
  control.note(metrology::implausibleDeviations(samples));
  control.note(unitMismatchWarnings(unstated, unit));
  const double per = unit ? millimetresPer(unit->unit) : 1.0;
  const comp::FormatTraits tr = comp::traits(format);
  const comp::AxisErrorTable raw = inUnit(comp::tableFromIso230_2(iso, request.axis), per);
  const comp::AxisErrorTable t = comp::fitToTarget(raw, tr, max_points);
  if (t.nominal != raw.nominal) noteResampled(control, raw.size(), t.size(), tr.even_spacing);
  if (!iso.bidirectional && control.notice)
    control.notice(
        "unidirectional data: the one direction's mean deviations are used for both directions");
  Built b;
  io::CompensationTableSummary& s = b.summary;
  s.iso = io::CompensationTableSummary::Iso{iso.E / per, iso.B / per, iso.M / per};
  s.input_rows = raw.size();
  s.rows = t.size();
  s.first = t.nominal.front();
  s.last = t.nominal.back();
  s.axis = t.axis;
  for (std::size_t i = 0; i < t.size(); ++i) {
    s.max_correction =
        tr.bidirectional
            ? std::max({s.max_correction, std::abs(t.error_up[i]), std::abs(t.error_down[i])})
            : std::max(s.max_correction, std::abs(t.meanError(i)));
  }
  b.text = axisTableText(t, format, request);
  if (!tr.bidirectional && iso.bidirectional && control.notice)
    control.notice(fmt::format(
        "{} has one table per axis: wrote the mean of both directions; the reversal (B = {:.6g} "
        "{}) is left to the control's backlash compensation",
        request.format,
        iso.B / per,
        unitName(unit)));
  return b;
}

/// The straightness table of the data (line removed as request.line), fitted to the format, in
/// the machine's unit.
Built buildCrossTable(const CompensationTableRequest& request,
                      comp::TableFormat format,
                      std::size_t max_points,
                      const std::optional<MachineUnit>& unit,
                      const RunControl& control) {
  io::Profile p = io::readStraightness(request.data);
  const double per = unit ? millimetresPer(unit->unit) : 1.0;
  for (auto* column : {&p.position, &p.value})
    for (double& v : *column) v /= per;
  comp::CrossAxisTable raw =
      comp::crossTableFromPoints(request.input_axis, request.output_axis, p.position, p.value);
  if (request.line != "raw") {
    const metrology::ReferenceLine line = request.line == "lsq"
                                              ? metrology::leastSquaresLine(raw.position, raw.error)
                                              : metrology::endpointLine(raw.position, raw.error);
    for (std::size_t i = 0; i < raw.position.size(); ++i) raw.error[i] -= line.at(raw.position[i]);
  }
  const comp::FormatTraits tr = comp::traits(format);
  const comp::CrossAxisTable t = comp::fitToTarget(raw, tr, max_points);
  if (t.position != raw.position)
    noteResampled(control, raw.position.size(), t.position.size(), true);
  Built b;
  io::CompensationTableSummary& s = b.summary;
  s.input_rows = raw.position.size();
  s.rows = t.position.size();
  s.first = t.position.front();
  s.last = t.position.back();
  s.axis = t.output_axis;
  s.input_axis = t.input_axis;
  for (double e : t.error) s.max_correction = std::max(s.max_correction, std::abs(e));
  b.text = format == comp::TableFormat::kSiemensCec
               ? comp::writeSiemensCec(comp::siemensCecFromTable(t, request.table_index))
               : comp::writeIsgCsv(std::vector<comp::IsgBlock>{comp::isgBlockFromTable(t)});
  return b;
}

}  // namespace

bool CompensationTableRequest::crossAxis() const {
  return format == "siemens-cec" || (format == "isg" && !output_axis.empty());
}

void CompensationTableRequest::validate() const {
  static_cast<void>(comp::parseTableFormat(format));
  if (crossAxis()) {
    if (input_axis.empty() || output_axis.empty())
      throw InvalidArgument(fmt::format(
          "--format {} with straightness data needs --input-axis and --output-axis", format));
  } else if (axis.empty()) {
    throw InvalidArgument(fmt::format("--axis is required for --format {}", format));
  }
  PKM_CHECK(line == "endpoint" || line == "lsq" || line == "raw",
            "--line '{}': expected endpoint, lsq or raw",
            line);
  PKM_CHECK(encoder == 0 || encoder == 1, "--encoder must be 0 or 1, got {}", encoder);
  PKM_CHECK(
      table_index >= 0 && table_index <= 1000, "--table must be in [0, 1000], got {}", table_index);
  PKM_CHECK(!data.empty(), "give at least one --data file");
  if (out.empty()) throw IoError("give --out FILE");
}

CompensationTableResult writeCompensationTable(const CompensationTableRequest& request,
                                               const RunControl& control) {
  request.validate();
  const comp::TableFormat format = comp::parseTableFormat(request.format);
  const std::size_t max_points =
      request.max_points.value_or(comp::traits(format).default_max_points);
  const std::optional<MachineUnit> unit = machineUnit(request.machine, request.ini);
  Built b = request.crossAxis() ? buildCrossTable(request, format, max_points, unit, control)
                                : buildAxisTable(request, format, max_points, unit, control);
  std::error_code ec;
  if (!request.force && std::filesystem::exists(request.out, ec))
    throw IoError(fmt::format("{}: exists; refusing to overwrite (use --force)", request.out));
  io::writeFileAtomic(request.out, b.text, io::Overwrite::kAllow);
  b.summary.format = request.format;
  b.summary.unit = unitName(unit);
  b.summary.out = request.out;
  return {std::move(b.summary), std::move(b.text)};
}

}  // namespace pkm::workflow
