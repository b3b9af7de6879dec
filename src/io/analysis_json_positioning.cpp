// The JSON documents of the positioning analyses (analysis_report.hpp): iso230-2, straightness,
// parallelism, squareness.
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "io/detail/uncertainty_json.hpp"
#include "pkm/io/analysis_report.hpp"

namespace pkm::io {
namespace {

using Json = nlohmann::ordered_json;

Json targetJson(const metrology::TargetStatistics& t) {
  return Json{{"target", t.target},
              {"mean_up", t.mean_up},
              {"mean_down", t.mean_down},
              {"mean", t.mean},
              {"reversal", t.reversal},
              {"s_up", t.s_up},
              {"s_down", t.s_down},
              {"repeatability_up", t.repeatability_up},
              {"repeatability_down", t.repeatability_down},
              {"repeatability", t.repeatability},
              {"runs_up", t.runs_up},
              {"runs_down", t.runs_down}};
}

}  // namespace

const char* toString(ParallelismPlane plane) {
  return plane == ParallelismPlane::kHorizontal ? "horizontal" : "vertical";
}

std::string analysisJson(const Iso230_2Report& report) {
  const metrology::Iso230_2Result& r = report.result;
  Json j{{"B", r.B},
         {"B_mean", r.B_mean},
         {"R_up", r.R_up},
         {"R_down", r.R_down},
         {"R", r.R},
         {"E_up", r.E_up},
         {"E_down", r.E_down},
         {"E", r.E},
         {"M", r.M},
         {"A_up", r.A_up},
         {"A_down", r.A_down},
         {"A", r.A},
         {"bidirectional", r.bidirectional},
         {"coverage_factor", report.coverage}};
  Json targets = Json::array();
  for (const auto& t : r.targets) targets.push_back(targetJson(t));
  j["targets"] = std::move(targets);
  j["iso230_2_conditions"] =
      Json{{"met", report.nonconformities.empty()}, {"nonconformities", report.nonconformities}};
  if (!report.warnings.empty()) j["warnings"] = report.warnings;
  j["uncertainty"] = detail::uncertaintyJson(report.uncertainty);
  if (!report.conformance.empty()) j["conformance"] = detail::conformanceJson(report.conformance);
  return detail::documentText(j);
}

std::string analysisJson(const StraightnessReport& report) {
  const metrology::StraightnessResult& r = report.result;
  const std::vector<double>& position = report.position;
  Json j{{"reference", std::string(metrology::toString(report.reference))},
         {"slope", r.line.slope},
         {"intercept", r.line.intercept},
         {"straightness", r.straightness},
         {"points", position.size()}};
  if (report.raw)
    j["raw"] = Json{{"points", report.raw->points}, {"straightness", report.raw->straightness}};
  if (!r.contact_points.empty()) {
    Json contacts = Json::array();
    for (std::size_t k : r.contact_points) {
      contacts.push_back(Json{{"position", position[k]},
                              {"deviation", report.deviation[k]},
                              {"residual", r.residuals[k]}});
    }
    j["contact_points"] = std::move(contacts);
  }
  Json residuals = Json::array();
  for (std::size_t k = 0; k < position.size(); ++k) {
    residuals.push_back(Json::array({position[k], r.residuals[k]}));
  }
  j["residuals"] = std::move(residuals);
  j["uncertainty"] = detail::uncertaintyJson(report.uncertainty);
  return detail::documentText(j);
}

std::string analysisJson(const ParallelismReport& report) {
  const metrology::ParallelismResult& r = report.result;
  const bool horizontal = report.plane == ParallelismPlane::kHorizontal;
  Json j{{"plane", toString(report.plane)},
         {"line", std::string(metrology::toString(report.line))},
         {"reference_slope", r.reference_slope},
         {"axis_slope", r.axis_slope},
         {"slope_difference", r.slope_difference},
         {horizontal ? "dgamma" : "dalpha", r.slope_difference},
         {"parallelism", r.parallelism},
         {"max_deviation", r.max_deviation}};
  if (report.sxP) j["sxP"] = *report.sxP;
  if (report.szP) j["szP"] = *report.szP;
  Json profile = Json::array();
  for (std::size_t k = 0; k < report.axis_position.size(); ++k) {
    profile.push_back(Json::array({report.axis_position[k], r.deviations[k]}));
  }
  j["deviations"] = std::move(profile);
  j["uncertainty"] = detail::uncertaintyJson(report.uncertainty);
  return detail::documentText(j);
}

std::string analysisJson(const SquarenessReport& report) {
  const metrology::FaceDiagonalResult& r = report.result;
  Json j{{"squareness", r.squareness},
         {"residual_rms", r.residual_rms},
         {"diagonals", report.diagonals},
         {"points", r.points_used}};
  if (r.scale) {
    j["scale"] = Json::array({(*r.scale)[0], (*r.scale)[1]});
    j["scale_model"] = r.scale_per_axis ? "per_axis" : "common";
  }
  j["uncertainty"] = detail::uncertaintyJson(report.uncertainty, report.monte_carlo);
  return detail::documentText(j);
}

}  // namespace pkm::io
