// `pkm analyze iso230-2 | straightness | parallelism` as workflows
// (workflow/analyze_positioning.hpp).
#include "pkm/workflow/analyze_positioning.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>

#include "data_errors.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/environment_records.hpp"
#include "pkm/io/positioning_files.hpp"
#include "pkm/metrology/iso230_2_conformity.hpp"
#include "pkm/metrology/positioning_uncertainty.hpp"
#include "pkm/metrology/profile_uncertainty.hpp"
#include "pkm/metrology/squareness_uncertainty.hpp"
#include "pkm/workflow/machine_unit.hpp"

namespace pkm::workflow {
namespace {

void requireData(const std::vector<io::NamedText>& data, const char* what) {
  if (data.empty()) throw IoError(fmt::format("give at least one {} file", what));
}

}  // namespace

void Iso230_2Request::validate() const {
  requireData(data, "data");
  if (!(std::isfinite(coverage) && coverage > 0.0))
    throw InvalidArgument(fmt::format("ISO 230-2: coverage factor must be > 0, got {}", coverage));
}

void StraightnessRequest::validate() const { requireData(data, "data"); }

void ParallelismRequest::validate() const {
  requireData(reference, "reference");
  requireData(axis, "axis");
  for (int sign : {reference_sign, axis_sign})
    if (sign != 1 && sign != -1)
      throw InvalidArgument(fmt::format("parallelism: a beam sign must be +1 or -1, got {}", sign));
}

namespace {

io::Iso230_2Report iso230_2(const Iso230_2Request& request) {
  const std::optional<MachineUnit> unit = machineUnit(request.machine, request.ini);
  std::vector<std::string> unstated;
  const std::vector<metrology::PositioningSample> samples =
      io::readPositioningSamples(request.data, request.columns, &unstated);
  io::Iso230_2Report report{
      metrology::evaluateIso230_2(samples, {.coverage_factor = request.coverage}),
      request.coverage,
      metrology::iso230_2Nonconformities(samples),
      metrology::implausibleDeviations(samples),
      {},
      {}};
  for (std::string& w : unitMismatchWarnings(unstated, unit))
    report.warnings.push_back(std::move(w));
  if (request.strict && !(report.nonconformities.empty() && report.warnings.empty())) {
    std::vector<std::string> all = report.nonconformities;
    all.insert(all.end(), report.warnings.begin(), report.warnings.end());
    throw InvalidArgument(fmt::format("--strict: {}", fmt::join(all, "; ")));
  }
  report.uncertainty = metrology::iso230_2Uncertainty(
      report.result,
      metrology::withRecordedConditions(request.uncertainty,
                                        io::readEnvironmentRecords(request.data)),
      request.coverage);
  report.conformance = metrology::decideIso230_2Conformance(report.uncertainty, request.tolerances);
  return report;
}

io::StraightnessReport straightness(const StraightnessRequest& request) {
  const io::Profile points = io::readStraightnessPoints(request.data);
  io::Profile p = io::perTargetMean(points);
  io::StraightnessReport report;
  report.reference = request.reference;
  if (points.position.size() > p.position.size())
    report.raw = io::StraightnessReport::Raw{
        points.position.size(),
        metrology::evaluateStraightness(points.position, points.value, request.reference)
            .straightness};
  report.result = metrology::evaluateStraightness(p.position, p.value, request.reference);
  report.uncertainty = {metrology::straightnessUncertainty(
      report.result.straightness, p.position, points.position, points.value, request.uncertainty)};
  report.position = std::move(p.position);
  report.deviation = std::move(p.value);
  return report;
}

io::ParallelismReport parallelism(const ParallelismRequest& request) {
  const io::Profile ref = io::readStraightness(request.reference);
  io::Profile axis = io::readStraightness(request.axis);
  io::ParallelismReport report;
  report.plane = request.plane;
  report.line = request.line;
  report.result = metrology::evaluateParallelism({ref.position, ref.value, request.reference_sign},
                                                 {axis.position, axis.value, request.axis_sign},
                                                 {request.line});
  const double difference = report.result.slope_difference;
  if (request.plane == io::ParallelismPlane::kVertical)
    report.sxP = metrology::pkmSquarenessFromSlopes(0.0, difference, 0.0).sxP;
  else if (request.szX2)
    report.szP = metrology::pkmSquarenessFromSlopes(difference, 0.0, *request.szX2).szP;
  if (ref.position.size() >= 3 && axis.position.size() >= 3) {
    const auto lsq = metrology::StraightnessReference::kLeastSquares;
    const std::vector<double> ref_r =
        metrology::evaluateStraightness(ref.position, ref.value, lsq).residuals;
    const std::vector<double> axis_r =
        metrology::evaluateStraightness(axis.position, axis.value, lsq).residuals;
    report.uncertainty = {metrology::parallelismUncertainty(report.result.parallelism,
                                                            {ref.position, ref_r, ref.value},
                                                            {axis.position, axis_r, axis.value},
                                                            request.uncertainty)};
    const auto [lo, hi] = std::minmax_element(axis.position.begin(), axis.position.end());
    const metrology::UncertaintyBudget& p = report.uncertainty.front();
    if (report.sxP)
      report.uncertainty.push_back(metrology::eq11Uncertainty(p, *hi - *lo, 1, "sxP", *report.sxP));
    if (report.szP)
      report.uncertainty.push_back(
          metrology::eq11Uncertainty(p, *hi - *lo, -1, "szP", *report.szP));
  }
  report.axis_position = std::move(axis.position);
  return report;
}

}  // namespace

io::Iso230_2Report analyzeIso230_2(const Iso230_2Request& request) {
  request.validate();
  return detail::namingData({request.data}, [&] { return iso230_2(request); });
}

io::StraightnessReport analyzeStraightness(const StraightnessRequest& request) {
  request.validate();
  return detail::namingData({request.data}, [&] { return straightness(request); });
}

io::ParallelismReport analyzeParallelism(const ParallelismRequest& request) {
  request.validate();
  return detail::namingData({request.reference, request.axis},
                            [&] { return parallelism(request); });
}

}  // namespace pkm::workflow
