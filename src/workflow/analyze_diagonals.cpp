// `pkm analyze diagonals` as a workflow (workflow/analyze_diagonals.hpp): the shifted-diagonal
// reader, the comparison with direct XY measurements and the three methods.
#include "pkm/workflow/analyze_diagonals.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <tuple>

#include "analyze_diagonal_inputs.hpp"
#include "analyze_diagonal_uncertainty.hpp"
#include "data_errors.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/environment_records.hpp"
#include "pkm/metrology/per_target.hpp"
#include "pkm/metrology/plane_prediction.hpp"

namespace pkm::workflow {
namespace detail {
namespace {

/// A shifted-diagonal measurement from a line file: its start corner's diagonal, the one axis its
/// end is shifted along, and its length error (mean deviation at the last target minus at the
/// first).
metrology::ShiftedDiagonalMeasurement shiftedLine(const io::TextTable& t,
                                                  const Eigen::Vector3d& size) {
  const LineFile f = readLineFile(t);
  const auto d = diagonalAt(f.start, size);
  if (!d) t.failHeader("line start is not a start corner of a body diagonal");
  std::vector<metrology::TargetSample> samples;
  for (std::size_t i = 0; i < f.target.size(); ++i)
    samples.push_back({f.target[i], f.deviation[i]});
  const metrology::TargetMeans means = metrology::perTargetMeans(samples);
  const double lo = means.target.front(), hi = means.target.back();
  if (std::abs(lo) > kCornerTolerance) t.failHeader("the first target must be 0 (the corner)");
  const Eigen::Vector3d end = f.start + hi * f.direction;
  const Eigen::Vector3d diff = end - (f.start + metrology::diagonalTravel(*d, size));
  metrology::ShiftedDiagonalMeasurement m{*d, -1, 0.0, means.mean.back() - means.mean.front()};
  for (int a = 0; a < 3; ++a) {
    if (std::abs(diff[a]) <= kCornerTolerance) continue;
    if (m.axis >= 0) t.failHeader("the end point is shifted along more than one axis");
    m.axis = a;
    m.shift = diff[a];
  }
  return m;
}

}  // namespace

std::vector<metrology::ShiftedDiagonalMeasurement> readShiftedMeasurements(
    const std::vector<io::NamedText>& data, const Eigen::Vector3d& size) {
  std::vector<metrology::ShiftedDiagonalMeasurement> ms;
  for (const io::NamedText& in : data) {
    const io::TextTable t = io::TextTable::parseData(in.text, in.name);
    if (isLineFile(t)) {
      ms.push_back(shiftedLine(t, size));
      continue;
    }
    const std::size_t cd = t.column({"diagonal"});
    const std::size_t ca = t.column({"shift_axis"});
    const std::size_t cs = t.column({"shift", "shift_mm"});
    const std::size_t ce = t.column({"length_error", "length_error_mm"});
    for (std::size_t r = 0; r < t.rows(); ++r) {
      const std::string_view a = t.text(r, ca);
      int axis = -2;
      if (a == "-" || a == "none") axis = -1;
      if (a == "x" || a == "X") axis = 0;
      if (a == "y" || a == "Y") axis = 1;
      if (a == "z" || a == "Z") axis = 2;
      if (axis == -2) t.fail(r, fmt::format("shift_axis '{}' is not x, y, z or none", a));
      ms.push_back({diagonalField(t, r, cd), axis, t.number(r, cs), t.number(r, ce)});
    }
  }
  return ms;
}

}  // namespace detail

namespace {

/// One XY line measurement compared with the 2-D prediction: the per-target mean deviation (a
/// straightness file's reading is the deviation itself) against the model along the line.
io::DiagonalComparison compareLine(const io::NamedText& in,
                                   const metrology::PlaneErrorModel& model) {
  const io::TextTable t = io::TextTable::parseData(in.text, in.name);
  const detail::LineFile f = detail::readLineFile(t);
  if (std::abs(f.direction.z()) > detail::kDirectionTolerance)
    t.failHeader("--compare: the line must lie in the XY plane");
  const std::string quantity = t.meta("quantity").value_or("linear");
  Eigen::Vector2d sensitive = f.direction.head<2>().normalized();
  const bool straightness = quantity == "straightness";
  if (straightness) {
    const auto lateral = detail::metaVector(t, "lateral");
    if (!lateral) t.failHeader("--compare: a straightness file needs '# lateral' metadata");
    sensitive = lateral->head<2>().normalized();
  } else if (quantity != "linear") {
    t.failHeader(fmt::format("--compare: quantity '{}' is not linear or straightness", quantity));
  }
  std::vector<metrology::TargetSample> samples;
  for (std::size_t i = 0; i < f.target.size(); ++i)
    samples.push_back({f.target[i], straightness ? f.deviation[i] + f.target[i] : f.deviation[i]});
  const metrology::TargetMeans m = metrology::perTargetMeans(samples);
  return {in.name,
          quantity,
          metrology::comparePlanePrediction(model,
                                            f.start.head<2>(),
                                            f.direction.head<2>().normalized(),
                                            sensitive,
                                            m.target,
                                            m.mean,
                                            straightness)};
}

std::vector<io::DiagonalComparison> compareAll(const DiagonalsRequest& request,
                                               const metrology::PlaneErrorModel& model) {
  std::vector<io::DiagonalComparison> out;
  for (const io::NamedText& in : request.compare) out.push_back(compareLine(in, model));
  return out;
}

void setBudgets(io::DiagonalsReport& report, detail::SquarenessBudgets budgets) {
  report.uncertainty = std::move(budgets.linear);
  report.monte_carlo = std::move(budgets.monte_carlo);
}

void body(const DiagonalsRequest& request, const RunControl& control, io::DiagonalsReport& report) {
  const std::vector<metrology::BodyDiagonalSample> samples =
      detail::readBodySamples(request.data, request.size);
  // ISO 230-2 needs ≥ 2 runs per target and direction on every diagonal.
  std::map<std::tuple<int, double, int>, int> per_target;
  for (const auto& s : samples)
    ++per_target[{static_cast<int>(s.diagonal), s.position, s.direction}];
  metrology::BodyDiagonalOptions options;
  options.iso.coverage_factor = request.coverage;
  options.iso230_2 = std::all_of(
      per_target.begin(), per_target.end(), [](const auto& kv) { return kv.second >= 2; });
  if (!options.iso230_2)
    control.note({"ISO 230-2 statistics need at least 2 runs per target and direction; omitted"});
  report.body = metrology::evaluateBodyDiagonals(samples, request.size, options);
  setBudgets(report,
             detail::bodySquarenessBudgets(
                 samples, *report.body, request.size, request.uncertainty, request.monte_carlo));
}

void step(const DiagonalsRequest& request, io::DiagonalsReport& report) {
  const std::vector<metrology::StepDiagonalPass> passes =
      detail::readStepPasses(request.data, request.size);
  report.step = metrology::extractStepDiagonal(passes, request.size);
  report.compare = compareAll(request, metrology::planeModel(*report.step));
  setBudgets(report,
             detail::stepSquarenessBudgets(
                 passes, *report.step, request.size, request.uncertainty, request.monte_carlo));
}

void shifted(const DiagonalsRequest& request, io::DiagonalsReport& report) {
  const std::vector<metrology::ShiftedDiagonalMeasurement> ms =
      detail::readShiftedMeasurements(request.data, request.size);
  report.shifted = metrology::evaluateShiftedDiagonals(ms, request.size);
  report.compare = compareAll(request, metrology::planeModel(*report.shifted));
  setBudgets(report,
             detail::shiftedSquarenessBudgets(
                 ms, *report.shifted, request.size, request.uncertainty, request.monte_carlo));
}

}  // namespace

void DiagonalsRequest::validate() const {
  if (data.empty()) throw IoError("give at least one data file");
  metrology::requireBoxSize(size);
  if (method == io::DiagonalMethod::kBody && !compare.empty())
    throw InvalidArgument("--compare: needs --method step or shifted");
}

io::DiagonalsReport analyzeDiagonals(const DiagonalsRequest& request, const RunControl& control) {
  request.validate();
  return detail::namingData({request.data, request.compare}, [&] {
    // The budgets at the conditions the files record (docs/analysis.md, "Measurement conditions").
    DiagonalsRequest r = request;
    r.uncertainty = metrology::withRecordedConditions(request.uncertainty,
                                                      io::readEnvironmentRecords(request.data));
    io::DiagonalsReport report;
    report.method = r.method;
    report.size = r.size;
    switch (r.method) {
      case io::DiagonalMethod::kBody:
        body(r, control, report);
        break;
      case io::DiagonalMethod::kStep:
        step(r, report);
        break;
      case io::DiagonalMethod::kShifted:
        shifted(r, report);
        break;
    }
    return report;
  });
}

}  // namespace pkm::workflow
