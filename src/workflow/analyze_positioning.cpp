// `pkm analyze iso230-2 | straightness | parallelism` as workflows
// (workflow/analyze_positioning.hpp).
#include "pkm/workflow/analyze_positioning.hpp"

#include <fmt/format.h>

#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/io/positioning_files.hpp"

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

io::Iso230_2Report analyzeIso230_2(const Iso230_2Request& request) {
  request.validate();
  const std::vector<metrology::PositioningSample> samples =
      io::readPositioningSamples(request.data);
  return {metrology::evaluateIso230_2(samples, {.coverage_factor = request.coverage}),
          request.coverage};
}

void StraightnessRequest::validate() const { requireData(data, "data"); }

io::StraightnessReport analyzeStraightness(const StraightnessRequest& request) {
  request.validate();
  io::Profile p = io::readStraightness(request.data);
  io::StraightnessReport report;
  report.reference = request.reference;
  report.result = metrology::evaluateStraightness(p.position, p.value, request.reference);
  report.position = std::move(p.position);
  report.deviation = std::move(p.value);
  return report;
}

void ParallelismRequest::validate() const {
  requireData(reference, "reference");
  requireData(axis, "axis");
  for (int sign : {reference_sign, axis_sign})
    if (sign != 1 && sign != -1)
      throw InvalidArgument(fmt::format("parallelism: a beam sign must be +1 or -1, got {}", sign));
}

io::ParallelismReport analyzeParallelism(const ParallelismRequest& request) {
  request.validate();
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
  report.axis_position = std::move(axis.position);
  return report;
}

}  // namespace pkm::workflow
