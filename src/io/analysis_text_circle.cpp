// The tables of the circle analyses (analysis_text.hpp): circle, circular (ISO 230-4),
// probe-offset (Lee et al. 2019).
#include <fmt/format.h>

#include <cmath>
#include <string>

#include "io/detail/uncertainty_json.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/analysis_text.hpp"

namespace pkm::io {
namespace {

/// 9 significant digits, "-" when not finite.
std::string num9(double v) { return std::isfinite(v) ? fmt::format("{:.9g}", v) : "-"; }

}  // namespace

std::string analysisText(const CircleReport& report) {
  const metrology::CircleFit& lsc = report.lsc;
  const metrology::MinZoneCircle& mzc = report.mzc;
  std::string out = fmt::format("circle ({} points)\n", report.sources.size());
  if (report.has_lsc) {
    out += fmt::format("LSC centre\t{}\t{}\nLSC radius\t{}\nLSC diameter\t{}\n",
                       num9(lsc.circle.center.x()),
                       num9(lsc.circle.center.y()),
                       num9(lsc.circle.radius),
                       num9(2.0 * lsc.circle.radius));
    out += fmt::format(
        "LSC iterations\t{}\nLSC converged\t{}\n", lsc.iterations, lsc.converged ? "yes" : "no");
    out += fmt::format("roundness LSC\t{}\n", num9(lsc.roundness));
  }
  if (!report.has_mzc) return out + detail::uncertaintyText(report.uncertainty);
  out += fmt::format("roundness MZC\t{}\n", num9(mzc.roundness));
  out += fmt::format("MZC centre\t{}\t{}\nMZC radii\t{}\t{}\nMZC certified\t{}\n",
                     num9(mzc.center.x()),
                     num9(mzc.center.y()),
                     num9(mzc.inner_radius),
                     num9(mzc.outer_radius),
                     mzc.certified ? "yes" : "no");
  for (const metrology::ZoneContact& c : mzc.contacts)
    out += fmt::format("MZC contact\t{}\t{}\t{}\t{}:{}\n",
                       c.outer ? "outer" : "inner",
                       num9(c.point.x()),
                       num9(c.point.y()),
                       report.sources[c.index].name,
                       report.sources[c.index].line);
  out += detail::uncertaintyText(report.uncertainty);
  return out;
}

std::string analysisText(const CircularReport& report) {
  const metrology::CircularTestResult& r = report.result;
  std::string out = fmt::format("ISO 230-4 circular test ({} CW, {} CCW points, centre {})\n",
                                report.points_cw,
                                report.points_ccw,
                                centreName(r.centre));
  out += fmt::format("G cw\t{}\nG ccw\t{}\nG(b)\t{}\nH\t{}\nH at deg\t{}\n",
                     num9(r.cw.circular_deviation),
                     num9(r.ccw.circular_deviation),
                     num9(r.bidirectional_deviation),
                     num9(r.hysteresis),
                     num9(radToDeg(r.hysteresis_angle)));
  if (r.cw.radial_deviation_max)
    out += fmt::format("F cw max/min/mean\t{}\t{}\t{}\nF ccw max/min/mean\t{}\t{}\t{}\n",
                       num9(*r.cw.radial_deviation_max),
                       num9(*r.cw.radial_deviation_min),
                       num9(*r.cw.mean_radial_deviation),
                       num9(*r.ccw.radial_deviation_max),
                       num9(*r.ccw.radial_deviation_min),
                       num9(*r.ccw.mean_radial_deviation));
  out += detail::uncertaintyText(report.uncertainty);
  return out;
}

std::string analysisText(const ProbeOffsetReport& report) {
  const metrology::ProbeOffsetFit& fit = report.fit;
  const Eigen::Vector2d o = -fit.offset;
  std::string out = fmt::format("probe offset ({} touches, least squares)\n", report.touches);
  out += fmt::format(
      "offset d (spindle -> ball)\t{}\t{}\n", num9(fit.offset.x()), num9(fit.offset.y()));
  out += fmt::format("o_probe = -d (seed 003 eq. 8)\t{}\t{}\n", num9(o.x()), num9(o.y()));
  out += fmt::format("ring centre\t{}\t{}\nball path radius\t{}\nrms\t{}\n",
                     num9(fit.ring_center.x()),
                     num9(fit.ring_center.y()),
                     num9(fit.ball_path_radius),
                     num9(fit.rms));
  out +=
      fmt::format("iterations\t{}\nconverged\t{}\n", fit.iterations, fit.converged ? "yes" : "no");
  if (report.effective_stylus_radius)
    out +=
        fmt::format("effective stylus diameter\t{}\n", num9(2.0 * *report.effective_stylus_radius));
  if (const auto& p = report.paper) {
    out += fmt::format(
        "eq. 9 o_probe ({} runs)\t{}\t{}\n", p->runs, num9(p->eq9.x()), num9(p->eq9.y()));
    out += fmt::format(
        "eq. 8 o_probe ({} runs)\t{}\t{}\n", p->runs, num9(p->eq8.x()), num9(p->eq8.y()));
  }
  out += detail::uncertaintyText(report.uncertainty);
  return out;
}

}  // namespace pkm::io
