// The CSV rows of the limit checks and of the DRM circle (kinematics_csv.hpp).
#include "pkm/io/kinematics_csv.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cmath>
#include <vector>

#include "pkm/core/units.hpp"
#include "pkm/io/number_format.hpp"

namespace pkm::io {
namespace {

namespace kin = pkm::kinematics;

/// `v` (empty when infinite: the limit is disabled) and a comma.
void appendMargin(std::string& out, double v) {
  if (!std::isinf(v)) appendNumber(out, v);
  out += ',';
}

/// The violations, "KIND ITEM value=V limit=L" joined by "; " (joint angles in degrees), and a
/// newline.
void appendViolations(std::string& out, const std::vector<kin::LimitViolation>& violations) {
  std::vector<std::string> parts;
  for (const auto& v : violations) {
    const bool angle = v.kind == kin::LimitKind::kJointAngle;
    parts.push_back(fmt::format("{} {} value={:.6g} limit={:.6g}",
                                kin::toString(v.kind),
                                v.item,
                                angle ? radToDeg(v.value) : v.value,
                                angle ? radToDeg(v.limit) : v.limit));
  }
  out += fmt::format("{}\n", fmt::join(parts, "; "));
}

}  // namespace

std::string hexapodCheckCsvHeader() {
  return "row,status,min_stroke_margin,stroke_strut,min_base_angle_margin_deg,base_joint,"
         "min_platform_angle_margin_deg,platform_joint,min_leg_distance,leg_pair,interference_"
         "margin,condition_number,condition_margin,violations\n";
}

void appendHexapodCheckRow(std::string& o, std::size_t index, const kin::HexapodCheckResult& c) {
  o += std::to_string(index);
  o += ',';
  o += c.status();
  o += ',';
  // Smallest margin and the strut or joint it belongs to; both empty when the limit is disabled.
  for (const kin::StrutVector* margins :
       {&c.stroke_margin, &c.base_angle_margin, &c.platform_angle_margin}) {
    int k = 0;
    margins->minCoeff(&k);
    const double scale = margins == &c.stroke_margin ? 1.0 : radToDeg(1.0);
    appendMargin(o, (*margins)[k] * scale);
    o += std::isinf((*margins)[k]) ? std::string(",") : std::to_string(k) + ',';
  }
  appendMargin(o, c.min_leg_distance);
  o += c.closest_pair[0] >= 0 ? fmt::format("{}-{},", c.closest_pair[0], c.closest_pair[1])
                              : std::string(",");
  appendMargin(o, c.interference_margin);
  appendMargin(o, c.condition_number);
  appendMargin(o, c.condition_margin);
  appendViolations(o, c.violations);
}

std::string exechonCheckCsvHeader() {
  return "row,status,min_stroke_margin,stroke_leg,alpha_margin_deg,beta_margin_deg,c_margin_deg,"
         "a_margin_deg,wrist_at_pole,condition_number,condition_margin,violations\n";
}

void appendExechonCheckRow(std::string& o,
                           std::size_t index,
                           std::string_view status,
                           const kin::ExechonCheckResult& c) {
  o += fmt::format("{},{},", index, status);
  if (c.solver_status != "ok") {
    o += ",,,,,,,,,\n";
    return;
  }
  int k = 0;
  c.stroke_margin.minCoeff(&k);
  appendMargin(o, c.stroke_margin[k]);
  o += std::isinf(c.stroke_margin[k]) ? std::string(",") : fmt::format("{},", "ABC"[k]);
  for (double margin : {c.alpha_margin, c.beta_margin, c.c_margin, c.a_margin})
    appendMargin(o, std::isinf(margin) ? margin : margin * radToDeg(1.0));
  o += c.wrist_at_pole ? "1," : "0,";
  appendMargin(o, c.condition_number);
  appendMargin(o, c.condition_margin);
  appendViolations(o, c.violations);
}

std::string drmCircleCsv(const kin::DrmCircleResult& r) {
  std::string o = "theta_deg,phi_drm_deg,fit_deg,residual_deg\n";
  for (std::size_t i = 0; i < r.theta.size() && i < r.phi.size(); ++i) {
    appendNumber(o, radToDeg(r.theta[i]));
    o += ',';
    appendNumber(o, radToDeg(r.phi[i]));
    if (r.ok()) {  // no fit for a circle that failed part-way
      const double fit = kin::evaluateDrmPolynomial(r.coefficients, r.theta[i]);
      o += ',';
      appendNumber(o, radToDeg(fit));
      o += ',';
      appendNumber(o, radToDeg(r.phi[i] - fit));
    } else {
      o += ",,";
    }
    o += '\n';
  }
  o += fmt::format("# status {}\n", kin::toString(r.status));
  if (!r.ok()) return o + fmt::format("# failed at point {}\n", r.failed_index);
  o += "# fit phi(theta) = sum c_n theta^n, theta and phi in rad (seed 003 eq. 10)\n";
  for (std::size_t n = 0; n < r.coefficients.size(); ++n)
    o += fmt::format("# c{} {}\n", n, formatNumber(r.coefficients[n]));
  o += fmt::format("# max |phi_drm| {} deg\n", formatNumber(radToDeg(r.max_abs_phi)));
  o += fmt::format("# max fit deviation {} deg\n", formatNumber(radToDeg(r.max_fit_deviation)));
  return o;
}

}  // namespace pkm::io
