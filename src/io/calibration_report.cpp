// The hexapod calibration summary as JSON (calibration_report.hpp).
#include "pkm/io/calibration_report.hpp"

#include "detail/calibration_json.hpp"
#include "detail/calibration_uncertainty_json.hpp"

namespace pkm::io {
namespace {

namespace cal = pkm::calibration;
using detail::ordered_json;

using detail::frameJson;
using detail::identifiabilityJson;
using detail::residualJson;
using detail::tcpJson;
using detail::vectorJson;

ordered_json toJson(const cal::HoldoutErrors& e) {
  return {{"poses", e.poses},
          {"fk_failures", e.failures},
          {"mean", e.mean},
          {"rms", e.rms},
          {"max", e.max}};
}

ordered_json monteCarloJson(const HexapodCalibrationReport::MonteCarlo& m) {
  ordered_json j;
  j["trials"] = m.summary.trials;
  j["failures"] = m.summary.failures;
  j["not_converged"] = m.summary.not_converged;
  j["seconds"] = m.summary.seconds;
  j["sigma_position"] = m.sigma_position;
  j["sigma_orientation"] = m.sigma_orientation;
  j["sigma_gauge"] = m.sigma_gauge;
  j["parameter_sigma"] = vectorJson(m.summary.standard_deviation.data(), cal::kHexapodParameters);
  return j;
}

ordered_json parametersJson(const HexapodCalibrationReport& r) {
  const cal::HexapodCalibrationSummary& s = r.fit;
  // U (k) of each parameter with a budget; null for fixed parameters.
  std::vector<ordered_json> U(cal::kHexapodParameters);
  if (r.uncertainty) {
    const auto& p = r.uncertainty->parameters;
    for (std::size_t b = 0; b < p.parameter_indices.size(); ++b)
      if (p.parameter_indices[b] >= 0)
        U[static_cast<std::size_t>(p.parameter_indices[b])] =
            p.linear.budgets[b].expandedUncertainty();
  }
  ordered_json params = ordered_json::array();
  for (int k = 0; k < cal::kHexapodParameters; ++k) {
    params.push_back({{"name", cal::hexapodParameterName(k)},
                      {"free", r.free[static_cast<std::size_t>(k)]},
                      {"initial", s.initial(k)},
                      {"estimate", s.parameters(k)},
                      {"change", s.parameters(k) - s.initial(k)},
                      {"sigma", s.standard_deviation(k)}});
    if (r.uncertainty) params.back()["U"] = U[static_cast<std::size_t>(k)];
  }
  return params;
}

/// The members from "machine" to "residuals": what was fitted and how the solver did.
void addFit(const HexapodCalibrationReport& r, ordered_json& j) {
  const cal::HexapodCalibrationSummary& s = r.fit;
  j["machine"] = r.machine;
  j["units"] = toString(r.unit);
  j["data"] = r.data_notes;
  j["observations"] = {{"poses", r.poses},
                       {"points", r.points},
                       {"constrained_sets", r.constrained_sets},
                       {"distances", r.distances},
                       {"equations", r.equations}};
  j["target_offset"] = {r.target_offset.x(), r.target_offset.y(), r.target_offset.z()};
  j["solver"] = detail::solverJson(s);
  j["residuals"] = {{"before", residualJson(s.before)}, {"after", residualJson(s.after)}};
}

}  // namespace

std::string hexapodCalibrationJson(const HexapodCalibrationReport& r) {
  const cal::HexapodCalibrationSummary& s = r.fit;
  ordered_json j;
  addFit(r, j);
  if (r.holdout) {
    const Eigen::Vector3d& t = r.holdout->target_offset;
    j["holdout"] = {{"target_offset", {t.x(), t.y(), t.z()}},
                    {"before", toJson(r.holdout->before)},
                    {"after", toJson(r.holdout->after)}};
  }
  j["identifiability"] = identifiabilityJson(s.identifiability);
  if (s.measurement_frame) {
    j["measurement_frame"] = frameJson(*s.measurement_frame);
    j["measurement_frame"]["sigma"] = vectorJson(s.frame_standard_deviation.data(), 6);
  }
  j["world_frame"] = r.world_frame;
  if (r.registration) {
    const cal::FrameRegistration& f = r.registration->fit;
    j["registration"] = frameJson(f.world_T_measurement);
    j["registration"]["file"] = r.registration->file;
    j["registration"]["references"] = f.references;
    j["registration"]["residuals"] = {{"rms", f.rms}, {"max", f.max}};
    j["registration"]["reference_sigma"] = f.sigma;
    Eigen::Matrix<double, 6, 1> sd = f.covariance.diagonal().cwiseSqrt();
    j["registration"]["sigma"] = vectorJson(sd.data(), 6);
    j["registration"]["tcp_U"] = r.registration->tcp_U;
  }
  j["sigma"] = s.sigma;
  if (s.backlash)
    j["backlash"] = {{"values", vectorJson(s.backlash->data(), 6)},
                     {"sigma", vectorJson(s.backlash_standard_deviation.data(), 6)},
                     {"approach", "from the row order of each file (first row unknown)"}};
  j["worst_observations"] = detail::worstJson(r.worst);
  ordered_json map;
  map["poses"] = r.workspace_poses;
  map["before"] = tcpJson(r.tcp_before);
  if (r.monte_carlo) {
    map["after"] = tcpJson(r.monte_carlo->summary.tcp);
    j["monte_carlo"] = monteCarloJson(*r.monte_carlo);
  }
  j["tcp_error_map"] = map;
  j["parameters"] = parametersJson(r);
  j["outputs"] = {{"machine", r.out_machine}, {"hal", r.out_hal}, {"summary", r.out_summary}};
  if (r.uncertainty) {
    const std::string unit(toString(r.unit));
    j["uncertainty"] =
        detail::calibrationUncertaintyJson(detail::uncertaintyViewOf(*r.uncertainty, unit));
  }
  return j.dump(2) + "\n";
}

std::string hexapodCalibrationUncertaintyText(const HexapodCalibrationReport& r) {
  if (!r.uncertainty) return {};
  const std::string unit(toString(r.unit));
  return detail::calibrationUncertaintyText(detail::uncertaintyViewOf(*r.uncertainty, unit));
}

}  // namespace pkm::io
