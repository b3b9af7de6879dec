// The hexapod calibration summary as JSON (calibration_report.hpp).
#include "pkm/io/calibration_report.hpp"

#include <nlohmann/json.hpp>

#include "pkm/geometry/so3.hpp"

namespace pkm::io {
namespace {

namespace cal = pkm::calibration;
using nlohmann::ordered_json;

ordered_json vec(const double* data, int n) { return std::vector<double>(data, data + n); }

ordered_json toJson(const cal::HoldoutErrors& e) {
  return {{"poses", e.poses},
          {"fk_failures", e.failures},
          {"mean", e.mean},
          {"rms", e.rms},
          {"max", e.max}};
}

ordered_json toJson(const cal::ResidualStatistics& s) {
  return {
      {"equations", s.equations}, {"rms", s.rms}, {"max", s.max}, {"fk_failures", s.fk_failures}};
}

ordered_json toJson(const cal::TcpErrorStatistics& s) {
  return {{"samples", s.samples}, {"mean", s.mean}, {"p95", s.p95}, {"max", s.max}};
}

ordered_json frameJson(const geometry::RigidTransform& f) {
  const Eigen::Vector3d rpy = geometry::rpyFromRotation(f.rotation);
  return {{"position", {f.translation.x(), f.translation.y(), f.translation.z()}},
          {"rpy_deg", {radToDeg(rpy.x()), radToDeg(rpy.y()), radToDeg(rpy.z())}}};
}

ordered_json identifiabilityJson(const cal::Identifiability& id) {
  ordered_json j;
  j["parameters"] = id.parameters;
  j["rank"] = id.rank;
  j["condition_number"] = id.condition_number;
  j["unidentifiable"] = ordered_json::array();
  for (const auto& c : id.combinations) {
    ordered_json terms = ordered_json::object();
    for (const auto& [name, coef] : c.terms) terms[name] = coef;
    j["unidentifiable"].push_back(terms);
  }
  return j;
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
  j["parameter_sigma"] = vec(m.summary.standard_deviation.data(), cal::kHexapodParameters);
  return j;
}

ordered_json parametersJson(const HexapodCalibrationReport& r) {
  const cal::HexapodCalibrationSummary& s = r.fit;
  ordered_json params = ordered_json::array();
  for (int k = 0; k < cal::kHexapodParameters; ++k)
    params.push_back({{"name", cal::hexapodParameterName(k)},
                      {"free", r.free[static_cast<std::size_t>(k)]},
                      {"initial", s.initial(k)},
                      {"estimate", s.parameters(k)},
                      {"change", s.parameters(k) - s.initial(k)},
                      {"sigma", s.standard_deviation(k)}});
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
  j["solver"] = {{"converged", s.converged},
                 {"termination", s.termination},
                 {"iterations", s.iterations},
                 {"initial_cost", s.initial_cost},
                 {"final_cost", s.final_cost},
                 {"seconds", s.seconds}};
  j["residuals"] = {{"before", toJson(s.before)}, {"after", toJson(s.after)}};
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
    j["measurement_frame"]["sigma"] = vec(s.frame_standard_deviation.data(), 6);
  }
  j["sigma"] = s.sigma;
  if (s.backlash)
    j["backlash"] = {{"values", vec(s.backlash->data(), 6)},
                     {"sigma", vec(s.backlash_standard_deviation.data(), 6)},
                     {"approach", "from the row order of each file (first row unknown)"}};
  ordered_json worst = ordered_json::array();
  for (const ObservationResidual& w : r.worst)
    worst.push_back({{"source", w.source}, {"residual", w.residual}});
  j["worst_observations"] = worst;
  ordered_json map;
  map["poses"] = r.workspace_poses;
  map["before"] = toJson(r.tcp_before);
  if (r.monte_carlo) {
    map["after"] = toJson(r.monte_carlo->summary.tcp);
    j["monte_carlo"] = monteCarloJson(*r.monte_carlo);
  }
  j["tcp_error_map"] = map;
  j["parameters"] = parametersJson(r);
  j["outputs"] = {{"machine", r.out_machine}, {"hal", r.out_hal}, {"summary", r.out_summary}};
  return j.dump(2) + "\n";
}

}  // namespace pkm::io
