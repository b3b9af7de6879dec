// The Exechon calibration summary as JSON (exechon_calibration_report.hpp).
#include "pkm/io/exechon_calibration_report.hpp"

#include "detail/calibration_json.hpp"
#include "detail/calibration_uncertainty_json.hpp"

namespace pkm::io {
namespace {

namespace cal = pkm::calibration;
using detail::ordered_json;

ordered_json holdoutJson(const cal::HoldoutErrors& e) {
  return {{"poses", e.poses}, {"failures", e.failures}, {"rms", e.rms}, {"max", e.max}};
}

ordered_json hybridHoldoutJson(const cal::HoldoutErrors& e) {
  return {{"poses", e.poses}, {"rms", e.rms}, {"max", e.max}};
}

ordered_json statisticsJson(const DistanceStatistics& s) {
  return {{"points", s.points}, {"mean", s.mean}, {"p95", s.p95}, {"max", s.max}};
}

ordered_json monteCarloJson(const ExechonTripodReport::MonteCarlo& m, bool frame) {
  const cal::ExechonMonteCarloSummary& u = m.summary;
  ordered_json j;
  j["trials"] = u.trials;
  j["failures"] = u.failures;
  j["not_converged"] = u.not_converged;
  j["seconds"] = u.seconds;
  j["sigma_position"] = m.sigma_position;
  j["sigma_orientation"] = m.sigma_orientation;
  j["configurations"] = u.configurations;
  j["tool_sigma"] = detail::tcpJson(u.tool_sigma);
  j["tool_deviation"] = detail::tcpJson(u.tcp);
  j["parameter_sigma"] = detail::vectorJson(u.standard_deviation.data(), cal::kExechonParameters);
  if (frame) j["frame_sigma"] = detail::vectorJson(u.frame_standard_deviation.data(), 6);
  return j;
}

ordered_json parametersJson(const ExechonTripodReport& t, LengthUnit unit) {
  const cal::ExechonCalibrationSummary& s = t.fit;
  ordered_json params = ordered_json::array();
  for (int k = 0; k < cal::kExechonParameters; ++k)
    params.push_back({{"name", cal::exechonParameterName(k)},
                      {"unit", cal::exechonParameterIsLength(k) ? toString(unit) : "rad"},
                      {"free", t.free[static_cast<std::size_t>(k)]},
                      {"initial", s.initial(k)},
                      {"estimate", s.parameters(k)},
                      {"change", s.parameters(k) - s.initial(k)},
                      {"sigma", s.standard_deviation(k)}});
  if (t.uncertainty) {
    for (ordered_json& p : params) p["U"] = nullptr;
    const auto& u = t.uncertainty->parameters;
    for (std::size_t b = 0; b < u.parameter_indices.size(); ++b)
      if (u.parameter_indices[b] >= 0)
        params[static_cast<std::size_t>(u.parameter_indices[b])]["U"] =
            u.linear.budgets[b].expandedUncertainty();
  }
  return params;
}

ordered_json uncertaintyJson(const ExechonTripodReport& t, LengthUnit unit) {
  const std::string u(toString(unit));
  return detail::calibrationUncertaintyJson(detail::uncertaintyViewOf(*t.uncertainty, u));
}

/// The tripod members, added to the top level of the document.
void addTripod(const ExechonTripodReport& t, LengthUnit unit, ordered_json& j) {
  const cal::ExechonCalibrationSummary& s = t.fit;
  j["observations"] = {{"points", t.points}, {"equations", t.equations}};
  j["target_offset"] = {t.target_offset.x(), t.target_offset.y(), t.target_offset.z()};
  j["solver"] = detail::solverJson(s);
  j["residuals"] = {{"before", detail::residualJson(s.before)},
                    {"after", detail::residualJson(s.after)}};
  if (t.holdout)
    j["holdout"] = {{"before", holdoutJson(t.holdout->before)},
                    {"after", holdoutJson(t.holdout->after)}};
  j["identifiability"] = detail::identifiabilityJson(s.identifiability);
  if (s.measurement_frame) {
    j["measurement_frame"] = detail::frameJson(*s.measurement_frame);
    j["measurement_frame"]["sigma"] = detail::vectorJson(s.frame_standard_deviation.data(), 6);
  }
  j["sigma"] = s.sigma;
  j["worst_observations"] = detail::worstJson(s.worst);
  if (t.map_before) {
    ordered_json map{{"before", statisticsJson(*t.map_before)}};
    if (t.map_after) map["after"] = statisticsJson(*t.map_after);
    j["tcp_error_map"] = map;
  }
  if (t.monte_carlo)
    j["monte_carlo"] = monteCarloJson(*t.monte_carlo, s.measurement_frame.has_value());
  j["parameters"] = parametersJson(t, unit);
  if (t.uncertainty) j["uncertainty"] = uncertaintyJson(t, unit);
}

ordered_json hybridJson(const HybridSquarenessReport& h) {
  const cal::HybridCalibrationSummary& s = h.fit;
  const auto squareness = [](const kinematics::HybridSquareness& q) {
    return ordered_json{{"szX2", q.sz_x2}, {"sxP", q.sx_p}, {"syP", q.sy_p}, {"szP", q.sz_p}};
  };
  ordered_json j;
  j["observations"] = h.observations;
  j["known_errors"] = h.known_errors;
  j["tripod_error_motion"] = h.tripod_error_motion;
  j["squareness"] = squareness(s.squareness);
  j["sigma"] = {{"szX2", s.standard_deviation(0)},
                {"sxP", s.standard_deviation(1)},
                {"syP", s.standard_deviation(2)},
                {"szP", s.standard_deviation(3)}};
  const Eigen::Vector4d u = h.standardUncertainty();
  j["tripod_standard_uncertainty"] = {{"szX2", h.tripod_standard_uncertainty(0)},
                                      {"sxP", h.tripod_standard_uncertainty(1)},
                                      {"syP", h.tripod_standard_uncertainty(2)},
                                      {"szP", h.tripod_standard_uncertainty(3)}};
  j["standard_uncertainty"] = {{"szX2", u(0)}, {"sxP", u(1)}, {"syP", u(2)}, {"szP", u(3)}};
  j["solver"] = {{"converged", s.converged},
                 {"termination", s.termination},
                 {"iterations", s.iterations},
                 {"seconds", s.seconds}};
  j["residuals"] = {{"before", detail::residualJson(s.before)},
                    {"after", detail::residualJson(s.after)}};
  j["identifiability"] = {{"parameters", s.identifiability.parameters},
                          {"rank", s.identifiability.rank},
                          {"condition_number", s.identifiability.condition_number}};
  if (s.measurement_frame) j["measurement_frame"] = detail::frameJson(*s.measurement_frame);
  j["worst_observations"] = detail::worstJson(s.worst);
  if (h.holdout)
    j["holdout"] = {{"before", hybridHoldoutJson(h.holdout->before)},
                    {"after", hybridHoldoutJson(h.holdout->after)}};
  return j;
}

}  // namespace

std::string exechonCalibrationUncertaintyText(const ExechonTripodReport& tripod, LengthUnit unit) {
  if (!tripod.uncertainty) return {};
  const std::string u(toString(unit));
  return detail::calibrationUncertaintyText(detail::uncertaintyViewOf(*tripod.uncertainty, u));
}

std::string exechonCalibrationJson(const ExechonCalibrationReport& r) {
  ordered_json j;
  j["machine"] = r.machine;
  j["units"] = toString(r.unit);
  j["data"] = r.data_notes;
  if (r.tripod) addTripod(*r.tripod, r.unit, j);
  if (r.hybrid) j["hybrid"] = hybridJson(*r.hybrid);
  j["outputs"] = {{"machine", r.out_machine}, {"summary", r.out_summary}};
  if (!r.out_errors.empty()) j["outputs"]["errors"] = r.out_errors;
  return j.dump(2) + "\n";
}

}  // namespace pkm::io
