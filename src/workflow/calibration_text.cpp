// The text summaries of `pkm calibrate hexapod` and `pkm calibrate exechon`
// (workflow/calibration_text.hpp).
#include "pkm/workflow/calibration_text.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <vector>

#include "pkm/core/units.hpp"

namespace pkm::workflow {
namespace {

namespace cal = pkm::calibration;

/// "solver: ...", "identifiable: ..." and one "  not identifiable: ..." line per combination.
template <class Summary>
std::string solverText(const Summary& s, const std::string& hint) {
  std::string t = fmt::format("solver: {} iterations, {:.3f} s, {}\n",
                              s.iterations,
                              s.seconds,
                              s.converged ? "converged" : s.termination);
  t += hint;
  t += fmt::format("identifiable: {} of {} unknowns (condition number {:.4g})\n",
                   s.identifiability.rank,
                   s.identifiability.parameters,
                   s.identifiability.condition_number);
  for (const auto& c : s.identifiability.combinations) {
    std::string terms;
    for (const auto& [name, coef] : c.terms) terms += fmt::format(" {:+.3f}·{}", coef, name);
    t += fmt::format("  not identifiable:{}\n", terms);
  }
  return t;
}

/// "LABEL: RMS b -> a, max b -> a".
template <class Before, class After>
std::string beforeAfter(const std::string& label, const Before& before, const After& after) {
  return fmt::format("{}: RMS {:.6g} -> {:.6g}, max {:.6g} -> {:.6g}\n",
                     label,
                     before.rms,
                     after.rms,
                     before.max,
                     after.max);
}

/// The hexapod lines after the fitted residuals: largest residual, backlash, held-out error.
std::string hexapodChecksText(const io::HexapodCalibrationReport& rep, const std::string& unit) {
  const cal::HexapodCalibrationSummary& s = rep.fit;
  std::string t;
  if (!rep.worst.empty())
    t += fmt::format("largest residual after the fit: {} ({:.4g})\n",
                     rep.worst[0].source,
                     rep.worst[0].residual);
  if (s.backlash)
    t += fmt::format(
        "backlash per strut ({}): {:.4g}\n",
        unit,
        fmt::join(std::vector<double>(s.backlash->data(), s.backlash->data() + 6), ", "));
  if (rep.holdout) t += beforeAfter("held-out TCP error", rep.holdout->before, rep.holdout->after);
  return t;
}

/// The tripod fit's lines of the Exechon summary.
std::string tripodText(const io::ExechonCalibrationReport& rep, const io::ExechonTripodReport& tr) {
  const cal::ExechonCalibrationSummary& s = tr.fit;
  std::string t = fmt::format("calibrated {} from {} equations ({} tracker points)\n",
                              rep.machine,
                              tr.equations,
                              tr.points);
  t += solverText(s, "");
  t += beforeAfter(fmt::format("fitted residuals ({})", toString(rep.unit)), s.before, s.after);
  if (tr.holdout) t += beforeAfter("held-out target error", tr.holdout->before, tr.holdout->after);
  if (!s.worst.empty())
    t += fmt::format("largest residual after the fit: {} ({:.4g})\n",
                     s.worst.front().source,
                     s.worst.front().residual);
  if (tr.map_before)
    t += fmt::format(
        "working-volume tool error of the nominal controller (what calibration removes): mean "
        "{:.6g}, 95 % {:.6g}, max {:.6g}\n",
        tr.map_before->mean,
        tr.map_before->p95,
        tr.map_before->max);
  if (tr.map_after)
    t += fmt::format(
        "working-volume tool uncertainty after calibration (linearised covariance): mean {:.6g}, "
        "95 % {:.6g}, max {:.6g}\n",
        tr.map_after->mean,
        tr.map_after->p95,
        tr.map_after->max);
  if (tr.monte_carlo) {
    const cal::ExechonMonteCarloSummary& u = tr.monte_carlo->summary;
    t += fmt::format(
        "tool-point spread after calibration (Monte Carlo, {} trials, {} failed, {} "
        "configurations): mean {:.6g}, 95 % {:.6g}, max {:.6g}\n",
        u.trials,
        u.failures,
        u.configurations,
        u.tool_sigma.mean,
        u.tool_sigma.p95,
        u.tool_sigma.max);
  }
  return t;
}

/// The squareness fit's lines of the Exechon summary.
std::string hybridText(const io::ExechonCalibrationReport& rep,
                       const io::HybridSquarenessReport& h) {
  const cal::HybridCalibrationSummary& s = h.fit;
  constexpr double kMrad = 1e3;
  std::string t = fmt::format(
      "squareness from {} hybrid observations{}: szX2 {:.4f}, sxP {:.4f}, syP {:.4f}, szP {:.4f} "
      "mrad (sigma {:.2g}, {:.2g}, {:.2g}, {:.2g})\n",
      h.observations,
      h.tripod_error_motion ? " (with the calibrated tripod)" : "",
      kMrad * s.squareness.sz_x2,
      kMrad * s.squareness.sx_p,
      kMrad * s.squareness.sy_p,
      kMrad * s.squareness.sz_p,
      kMrad * s.standard_deviation(0),
      kMrad * s.standard_deviation(1),
      kMrad * s.standard_deviation(2),
      kMrad * s.standard_deviation(3));
  if (h.tripod_standard_uncertainty.any()) {
    const Eigen::Vector4d u = h.standardUncertainty();
    t += fmt::format(
        "  with the calibrated tripod's uncertainty: u {:.2g}, {:.2g}, {:.2g}, {:.2g} mrad\n",
        kMrad * u(0),
        kMrad * u(1),
        kMrad * u(2),
        kMrad * u(3));
  }
  t += beforeAfter(fmt::format("hybrid residuals ({})", toString(rep.unit)), s.before, s.after);
  if (h.holdout)
    t += beforeAfter("held-out hybrid target error", h.holdout->before, h.holdout->after);
  return t;
}

}  // namespace

std::string hexapodCalibrationText(const HexapodCalibrationRequest& request,
                                   const HexapodCalibrationResult& result) {
  const io::HexapodCalibrationReport& rep = result.report;
  const cal::HexapodCalibrationSummary& s = rep.fit;
  const std::string unit(toString(rep.unit));
  std::string t =
      fmt::format("calibrated {} from {} equations ({} poses, {} points, {} gauge sets)\n",
                  rep.machine,
                  rep.equations,
                  rep.poses,
                  rep.points,
                  rep.constrained_sets);
  const bool weak_gauges = !s.converged && rep.constrained_sets > 0 && request.prior_sigma == 0.0;
  t += solverText(s,
                  weak_gauges ? "  dial-gauge data see some combinations only weakly: "
                                "--prior-sigma (with --measurement-sigma) keeps them near the "
                                "machine file (docs/calibration.md)\n"
                              : "");
  t += beforeAfter(fmt::format("fitted residuals ({})", unit), s.before, s.after);
  t += hexapodChecksText(rep, unit);
  t += fmt::format(
      "workspace TCP error of the nominal controller (what calibration removes): "
      "mean {:.6g}, 95 % {:.6g}, max {:.6g}\n",
      rep.tcp_before.mean,
      rep.tcp_before.p95,
      rep.tcp_before.max);
  if (rep.monte_carlo) {
    const cal::TcpErrorStatistics& a = rep.monte_carlo->summary.tcp;
    t += fmt::format(
        "workspace TCP uncertainty after calibration (Monte Carlo, {} trials): mean "
        "{:.6g}, 95 % {:.6g}, max {:.6g}\n",
        request.monte_carlo,
        a.mean,
        a.p95,
        a.max);
  }
  t += io::hexapodCalibrationUncertaintyText(rep);
  if (rep.registration) {
    const cal::FrameRegistration& f = rep.registration->fit;
    t += fmt::format(
        "world frame registered on {} nests of {}: residual RMS {:.4g}, max {:.4g} {}; its "
        "uncertainty at the TCP (k = 2, worst workspace pose) {:.4g} {}\n",
        f.references,
        rep.registration->file,
        f.rms,
        f.max,
        unit,
        rep.registration->tcp_U,
        unit);
  } else if (rep.world_frame == "unregistered") {
    t += "world frame NOT registered: tracker-frame readings without --registration; the "
         "machine file is marked \"world_frame\": \"unregistered\" and goes into no controller\n";
  }
  if (!rep.out_machine.empty() && rep.out_hal.empty())
    t += fmt::format("wrote {}, {}\n", rep.out_machine, rep.out_summary);
  else if (!rep.out_machine.empty())
    t += fmt::format("wrote {}, {}, {}\n", rep.out_machine, rep.out_hal, rep.out_summary);
  return t;
}

std::string exechonCalibrationText(const ExechonCalibrationResult& result) {
  const io::ExechonCalibrationReport& rep = result.report;
  std::string t;
  if (rep.tripod) {
    t += tripodText(rep, *rep.tripod);
    t += io::exechonCalibrationUncertaintyText(*rep.tripod, rep.unit);
  }
  if (rep.hybrid) t += hybridText(rep, *rep.hybrid);
  if (!result.written.empty()) t += fmt::format("wrote {}\n", fmt::join(result.written, ", "));
  return t;
}

}  // namespace pkm::workflow
