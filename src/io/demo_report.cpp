// The report of `pkm demo` as text (demo_report.hpp).
#include "pkm/io/demo_report.hpp"

#include <fmt/format.h>

namespace pkm::io {

std::string hexapodDemoText(const HexapodDemoReport& r) {
  const std::string_view u = toString(r.unit);
  std::string t = r.description + "\n";
  t += fmt::format(
      "path         {} poses: circle of radius {:g} {} with z wave, tilt up to {:g} deg\n",
      r.points,
      r.radius,
      u,
      2 * radToDeg(r.tilt));
  t += "\nsummary\n";
  t += "  IK + checks  status counts:";
  for (const auto& [k, v] : r.statuses) t += fmt::format(" {} {}", k, v);
  t += fmt::format(
      "\n  conditioning scaled Jacobian condition number {:.2f} .. {:.2f} (limit {:g})\n",
      r.min_condition,
      r.max_condition,
      r.condition_limit);
  t += fmt::format(
      "  margins      smallest stroke margin {:.3f} {}, smallest joint-angle margin {:.2f} deg\n",
      r.min_stroke_margin,
      u,
      radToDeg(r.min_angle_margin));
  t += fmt::format("  FK (servo)   {} of {} converged; iterations:", r.converged, r.points);
  for (const auto& [k, v] : r.iterations) t += fmt::format(" {}x{}", v, k);
  t += fmt::format(
      "\n  round trip   max |p_FK - p| = {:.3g} {}, max rotation error = {:.3g} rad, max strut "
      "residual = {:.3g} {}\n",
      r.max_position_error,
      u,
      r.max_rotation_error,
      r.max_residual,
      u);
  t += fmt::format("  speed        {:.2f} us per forward solve ({} solves in {:.3f} s)\n",
                   1e6 * r.seconds / r.points,
                   r.points,
                   r.seconds);
  t +=
      fmt::format("  result       {}\n", r.pass ? "PASS: FK(IK(pose)) returns every pose" : "FAIL");
  return t;
}

std::string exechonDemoText(const ExechonDemoReport& r) {
  std::string t = fmt::format(
      "\nExechon       {} ({}): tripod with C/A wrist on X2 {:g}..{:g} mm and Y2 {:g}..{:g} mm\n",
      r.machine,
      r.source,
      r.x2_min,
      r.x2_max,
      r.y2_min,
      r.y2_max);
  if (r.path_solved) {
    t += fmt::format(
        "  tool path    {} poses (150 mm circle, z wave, tool leaning up to 15 deg): {} outside "
        "a limit\n",
        r.points,
        r.violations);
    t += fmt::format(
        "  FK (servo)   {} of {} converged, at most {} Newton steps, {:.2f} us per solve\n",
        r.converged,
        r.points,
        r.max_iterations,
        r.us_per_solve);
    t += fmt::format("  round trip   max |p_FK - p| = {:.3g} mm, max |u_FK - u| = {:.3g}\n",
                     r.max_position_error,
                     r.max_direction_error);
  }
  if (r.drm_status != "ok")
    t += fmt::format("  DRM          circle failed: {}\n", r.drm_status);
  else
    t += fmt::format(
        "  DRM          40 mm ring, vertical tool: max |phi_DRM| {:.3f} deg; 5th-order fit (seed "
        "003 eq. 10) max deviation {:.4f} deg (paper: < 0.1 deg on its machine)\n",
        radToDeg(r.drm_max_phi),
        radToDeg(r.drm_max_fit_deviation));
  t += fmt::format(
      "  volumetric   seed 000 errors over {} points of X2 0..4000 x Y 600 x Z 400 mm: max |dp| "
      "{:.3f} mm; exact vs first-order model differ by at most {:.2g} mm\n",
      r.volumetric_points,
      r.max_dp,
      r.max_dp_linear);
  t += fmt::format("  parallelism  PKM Y over 600 mm vs Y2: dz {:.3f} mm (sxP = {:.2f} mrad)\n",
                   r.parallelism_dz,
                   1e3 * r.sx_p);
  t += fmt::format("  result       {}\n",
                   r.pass ? "PASS: tool FK(IK(pose)) returns every pose" : "FAIL");
  return t;
}

}  // namespace pkm::io
