// The tables of the positioning analyses (analysis_text.hpp): iso230-2, straightness,
// parallelism, squareness.
#include <fmt/format.h>

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include "io/detail/uncertainty_json.hpp"
#include "pkm/io/analysis_text.hpp"

namespace pkm::io {
namespace {

/// 6 significant digits, "-" when not finite.
std::string cell(double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : "-"; }

}  // namespace

std::string analysisText(const Iso230_2Report& report) {
  const metrology::Iso230_2Result& r = report.result;
  std::string out = fmt::format(
      "ISO 230-2 positioning ({} targets, k = {})\n", r.targets.size(), report.coverage);
  out += "target\tmean_up\tmean_down\treversal\ts_up\ts_down\tR_up\tR_down\tR\n";
  for (const auto& t : r.targets) {
    out += fmt::format("{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\t{}\n",
                       cell(t.target),
                       cell(t.mean_up),
                       cell(t.mean_down),
                       cell(t.reversal),
                       cell(t.s_up),
                       cell(t.s_down),
                       cell(t.repeatability_up),
                       cell(t.repeatability_down),
                       cell(t.repeatability));
  }
  const std::vector<std::pair<const char*, double>> summary{{"B", r.B},
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
                                                            {"A", r.A}};
  for (const auto& [name, v] : summary) out += fmt::format("{}\t{}\n", name, cell(v));
  if (report.nonconformities.empty()) out += "conditions\tISO 230-2 test conditions met\n";
  for (const std::string& n : report.nonconformities) out += fmt::format("nonconforming\t{}\n", n);
  for (const std::string& w : report.warnings) out += fmt::format("warning\t{}\n", w);
  out += detail::uncertaintyText(report.uncertainty);
  out += detail::conformanceText(report.conformance);
  return out;
}

std::string analysisText(const StraightnessReport& report) {
  const metrology::StraightnessResult& r = report.result;
  std::string out = fmt::format("straightness ({} reference line, {} points)\n",
                                metrology::toString(report.reference),
                                report.position.size());
  out += fmt::format("slope\t{}\nintercept\t{}\nstraightness\t{}\n",
                     cell(r.line.slope),
                     cell(r.line.intercept),
                     cell(r.straightness));
  for (std::size_t k : r.contact_points) {
    out += fmt::format("contact\t{}\t{}\n", cell(report.position[k]), cell(r.residuals[k]));
  }
  if (report.raw)
    out += fmt::format("raw_points\t{}\nraw_straightness\t{}\n",
                       report.raw->points,
                       cell(report.raw->straightness));
  out += detail::uncertaintyText(report.uncertainty);
  return out;
}

std::string analysisText(const ParallelismReport& report) {
  const metrology::ParallelismResult& r = report.result;
  std::string out = fmt::format("parallelism ({} plane, {} representative lines)\n",
                                toString(report.plane),
                                metrology::toString(report.line));
  out += fmt::format(
      "reference_slope\t{}\naxis_slope\t{}\n{}\t{}\nparallelism\t{}\n"
      "max_deviation\t{}\n",
      cell(r.reference_slope),
      cell(r.axis_slope),
      report.plane == ParallelismPlane::kHorizontal ? "dgamma" : "dalpha",
      cell(r.slope_difference),
      cell(r.parallelism),
      cell(r.max_deviation));
  if (report.sxP) out += fmt::format("sxP\t{}\n", cell(*report.sxP));
  if (report.szP) out += fmt::format("szP\t{}\n", cell(*report.szP));
  out += detail::uncertaintyText(report.uncertainty);
  return out;
}

std::string analysisText(const SquarenessReport& report) {
  const metrology::FaceDiagonalResult& r = report.result;
  std::string out =
      fmt::format("face-diagonal squareness ({} diagonals, {} readings, {} PDGE tables)\n",
                  report.diagonals,
                  r.points_used,
                  report.pdge_tables);
  out += fmt::format(
      "squareness\t{} rad\nresidual_rms\t{}\n", cell(r.squareness), cell(r.residual_rms));
  if (r.scale) {
    out += fmt::format("scale\t{}\t{}\t({})\n",
                       cell((*r.scale)[0]),
                       cell((*r.scale)[1]),
                       r.scale_per_axis ? "per axis" : "common");
  }
  out += detail::uncertaintyText(report.uncertainty);
  out += detail::monteCarloText(report.uncertainty, report.monte_carlo);
  return out;
}

}  // namespace pkm::io
