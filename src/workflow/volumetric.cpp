// `pkm volumetric` (volumetric.hpp): the volumetric error over a grid or a list of commands.
#include "pkm/workflow/volumetric.hpp"

#include <fmt/format.h>

#include <cmath>
#include <string_view>

#include "pkm/core/error.hpp"
#include "pkm/io/csv.hpp"
#include "pkm/kinematics/hybrid_chain.hpp"

namespace pkm::workflow {
namespace {

namespace kin = pkm::kinematics;

/// "a:b:n" -> n values from a to b (n = 1: a alone).
std::vector<double> parseAxis(std::string_view text, const std::string& whole) {
  std::array<double, 3> v{};
  std::size_t pos = 0;
  for (std::size_t i = 0; i < 3; ++i) {
    const std::size_t colon = text.find(':', pos);
    const std::string_view field =
        text.substr(pos, colon == std::string_view::npos ? std::string_view::npos : colon - pos);
    if ((colon == std::string_view::npos) != (i == 2) || !io::parseFiniteDouble(field, v[i]))
      throw IoError(fmt::format("--grid '{}': expected X0:X1:NX,Y0:Y1:NY,Z0:Z1:NZ", whole));
    pos = colon + 1;
  }
  if (v[2] < 1 || v[2] > 10000 || v[2] != std::floor(v[2]))
    throw IoError(fmt::format(
        "--grid '{}': the number of points per axis must be an integer in [1, 10000]", whole));
  const auto n = static_cast<int>(v[2]);
  std::vector<double> out;
  for (int k = 0; k < n; ++k) out.push_back(n == 1 ? v[0] : v[0] + (v[1] - v[0]) * k / (n - 1));
  return out;
}

io::VolumetricRow evaluateRow(const kin::HybridMachineModel& model,
                              const kin::GeometricErrors& errors,
                              const kin::HybridCommand& command) {
  io::VolumetricRow row;
  row.command = command;
  row.tool = kin::hybridNominalToolPosition(model, command);
  try {
    row.dp = kin::hybridVolumetricError(model, errors, command);
    row.dp_linear = kin::hybridVolumetricErrorLinear(model, errors, command);
  } catch (const InvalidArgument&) {  // a table with "out_of_range": "error" does not cover it
    row.status = io::VolumetricRow::Status::kOutsideTable;
    return row;
  }
  row.status = kin::hybridWithinLimits(model, command) ? io::VolumetricRow::Status::kOk
                                                       : io::VolumetricRow::Status::kAxisLimit;
  return row;
}

/// Hands one row over, checking for cancellation every 4096 rows.
class RowEmitter {
 public:
  RowEmitter(const kin::HybridMachineModel& model,
             const kin::GeometricErrors& errors,
             const VolumetricSink& sink,
             const RunControl& control)
      : model_(model), errors_(errors), sink_(sink), control_(control) {}
  void operator()(const kin::HybridCommand& command) {
    if (count_ % 4096 == 0) control_.checkCancelled();
    ++count_;
    if (sink_.row) sink_.row(evaluateRow(model_, errors_, command));
  }
  [[nodiscard]] std::size_t count() const { return count_; }

 private:
  const kin::HybridMachineModel& model_;
  const kin::GeometricErrors& errors_;
  const VolumetricSink& sink_;
  const RunControl& control_;
  std::size_t count_ = 0;
};

}  // namespace

std::array<std::vector<double>, 3> parseVolumetricGrid(const std::string& text) {
  std::array<std::vector<double>, 3> axes;
  std::size_t pos = 0;
  for (std::size_t a = 0; a < 3; ++a) {
    const std::size_t comma = text.find(',', pos);
    if ((comma == std::string::npos) != (a == 2))
      throw IoError(fmt::format("--grid '{}': expected X0:X1:NX,Y0:Y1:NY,Z0:Z1:NZ", text));
    axes[a] = parseAxis(std::string_view(text).substr(
                            pos, comma == std::string::npos ? std::string::npos : comma - pos),
                        text);
    pos = comma + 1;
  }
  if (axes[0].size() * axes[1].size() * axes[2].size() > 10'000'000)
    throw IoError(fmt::format("--grid '{}': more than 10 million points", text));
  return axes;
}

void VolumetricRequest::validate() const {
  if (grid.has_value() == commands.has_value())
    throw IoError("give either a grid or a commands file");
  if (!grid) return;
  if (x2.has_value() != y2.has_value()) throw IoError("give both --x2 and --y2, or neither");
  static_cast<void>(parseVolumetricGrid(*grid));
}

std::size_t computeVolumetricErrors(const VolumetricRequest& request,
                                    const VolumetricSink& sink,
                                    const RunControl& control) {
  request.validate();
  const io::ExechonMachine machine = io::loadExechonMachine(request.machine);
  control.note(machine.notices);
  if (!machine.hybrid)
    throw IoError(
        fmt::format("{}: the machine has no \"hybrid\" section (X2/Y2 axes)", machine.source));
  const kin::HybridMachineModel& model = *machine.hybrid;
  const kin::GeometricErrors errors = io::loadGeometricErrors(request.errors);
  if (errors.unit != model.unit)
    throw IoError(fmt::format("{}: the errors are in {} but the machine {} is in {}",
                              request.errors,
                              toString(errors.unit),
                              machine.source,
                              toString(model.unit)));
  RowEmitter emit(model, errors, sink, control);
  if (request.grid) {
    const std::array<std::vector<double>, 3> axes = parseVolumetricGrid(*request.grid);
    if (sink.begin) sink.begin();
    for (double z : axes[2])
      for (double y : axes[1])
        for (double x : axes[0]) {
          const Eigen::Vector3d p(x, y, z);
          emit(request.x2 ? kin::hybridCommandForTool(model, p, *request.x2, *request.y2)
                          : kin::hybridCommandCentred(model, p));
        }
    return emit.count();
  }
  io::CsvReader reader(*request.commands, {"x2", "y2", "xp", "yp", "zp"});
  if (sink.begin) sink.begin();
  std::array<double, 5> row{};
  while (reader.next(row)) {
    kin::HybridCommand c;
    c.x2 = row[0];
    c.y2 = row[1];
    c.pkm = {row[2], row[3], row[4]};
    emit(c);
  }
  return emit.count();
}

}  // namespace pkm::workflow
