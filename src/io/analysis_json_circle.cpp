// The JSON documents of the circle analyses (analysis_report.hpp): circle, circular (ISO 230-4),
// probe-offset (Lee et al. 2019).
#include <nlohmann/json.hpp>
#include <string>
#include <utility>

#include "io/detail/uncertainty_json.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/analysis_report.hpp"

namespace pkm::io {
namespace {

using Json = nlohmann::ordered_json;
using metrology::Point2;

Json pair(const Point2& p) { return Json::array({p.x(), p.y()}); }

Json runJson(const metrology::CircularRun& r) {
  Json j{{"center", pair(r.center)}, {"radius", r.radius}, {"G", r.circular_deviation}};
  if (r.radial_deviation_max) {
    j["F_max"] = *r.radial_deviation_max;
    j["F_min"] = *r.radial_deviation_min;
    j["F_mean"] = *r.mean_radial_deviation;
  }
  return j;
}

}  // namespace

const char* centreName(metrology::CircularCentre centre) {
  switch (centre) {
    case metrology::CircularCentre::kLeastSquares:
      return "lsc";
    case metrology::CircularCentre::kMinimumZone:
      return "mzc";
    case metrology::CircularCentre::kNominal:
      return "nominal";
  }
  return "lsc";
}

std::string analysisJson(const CircleReport& report) {
  const metrology::CircleFit& lsc = report.lsc;
  const metrology::MinZoneCircle& mzc = report.mzc;
  Json contacts = Json::array();
  for (const metrology::ZoneContact& c : mzc.contacts)
    contacts.push_back(Json{{"circle", c.outer ? "outer" : "inner"},
                            {"x", c.point.x()},
                            {"y", c.point.y()},
                            {"index", c.index},
                            {"file", report.sources[c.index].name},
                            {"line", report.sources[c.index].line}});
  Json j{{"center", pair(lsc.circle.center)},
         {"radius", lsc.circle.radius},
         {"diameter", 2.0 * lsc.circle.radius},
         {"roundness_lsc", lsc.roundness},
         {"roundness_mzc", mzc.roundness},
         {"mzc_center", pair(mzc.center)},
         {"mzc_inner_radius", mzc.inner_radius},
         {"mzc_outer_radius", mzc.outer_radius},
         {"mzc_contacts", std::move(contacts)},
         {"mzc_certified", mzc.certified},
         {"rms", lsc.rms},
         {"iterations", lsc.iterations},
         {"converged", lsc.converged},
         {"points", report.sources.size()},
         {"uncertainty", detail::uncertaintyJson(report.uncertainty)}};
  // One circle asked for: its keys only, and which it is.
  if (!report.has_mzc)
    for (const char* k : {"roundness_mzc",
                          "mzc_center",
                          "mzc_inner_radius",
                          "mzc_outer_radius",
                          "mzc_contacts",
                          "mzc_certified"})
      j.erase(k);
  if (!report.has_lsc)
    for (const char* k :
         {"center", "radius", "diameter", "roundness_lsc", "rms", "iterations", "converged"})
      j.erase(k);
  if (!report.has_lsc || !report.has_mzc) j["fit"] = report.has_lsc ? "lsc" : "mzc";
  return detail::documentText(j);
}

std::string analysisJson(const CircularReport& report) {
  const metrology::CircularTestResult& r = report.result;
  return detail::documentText(Json{{"centre", centreName(r.centre)},
                                   {"G_cw", r.cw.circular_deviation},
                                   {"G_ccw", r.ccw.circular_deviation},
                                   {"G_bidirectional", r.bidirectional_deviation},
                                   {"H", r.hysteresis},
                                   {"H_angle_deg", radToDeg(r.hysteresis_angle)},
                                   {"common_center", pair(r.common_center)},
                                   {"cw", runJson(r.cw)},
                                   {"ccw", runJson(r.ccw)},
                                   {"points_cw", report.points_cw},
                                   {"points_ccw", report.points_ccw},
                                   {"uncertainty", detail::uncertaintyJson(report.uncertainty)}});
}

std::string analysisJson(const ProbeOffsetReport& report) {
  const metrology::ProbeOffsetFit& fit = report.fit;
  Json j{{"offset", pair(fit.offset)},
         {"o_probe", pair(-fit.offset)},
         {"ring_center", pair(fit.ring_center)},
         {"ball_path_radius", fit.ball_path_radius},
         {"rms", fit.rms},
         {"iterations", fit.iterations},
         {"converged", fit.converged},
         {"touches", report.touches},
         {"tool_direction", report.tool_plus_z ? "+z" : "-z"}};
  if (report.effective_stylus_radius) {
    j["effective_stylus_radius"] = *report.effective_stylus_radius;
    j["effective_stylus_diameter"] = 2.0 * *report.effective_stylus_radius;
  }
  if (report.paper) {
    j["eq9_o_probe"] = pair(report.paper->eq9);
    j["eq8_o_probe"] = pair(report.paper->eq8);
    j["eq_runs"] = report.paper->runs;
  }
  j["uncertainty"] = detail::uncertaintyJson(report.uncertainty);
  return detail::documentText(j);
}

}  // namespace pkm::io
