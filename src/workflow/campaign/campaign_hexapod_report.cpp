// The report section of the campaign step "hexapod-calibration": the calibration in words, the
// TCP error maps and the positioning plot, the identifiability and parameter tables.
#include <fmt/format.h>

#include <algorithm>

#include "campaign_hexapod_detail.hpp"
#include "campaign_steps.hpp"
#include "pkm/calibration/hexapod_parameters.hpp"

namespace pkm::workflow::campaign::detail {

namespace cal = pkm::calibration;

namespace {

/// The report section's paragraphs.
std::vector<std::string> paragraphs(const io::Scenario& scenario,
                                    std::uint64_t seed,
                                    std::size_t poses,
                                    std::size_t constrained_sets,
                                    const cal::HexapodCalibrationSummary& s) {
  const std::string data =
      constrained_sets > 0
          ? fmt::format("{} constrained-motion set(s) read by three dial gauges (seed 004 §3)",
                        constrained_sets)
          : fmt::format("{} pose observations", poses);
  std::vector<std::string> out = {
      fmt::format(
          "Scenario {} (seed {}): {}", scenario.campaign.name, seed, scenario.campaign.description),
      fmt::format("Calibration: {}, {} of {} parameter combinations "
                  "identifiable (condition number {:.3g}), {} LM iterations; residual "
                  "RMS {:.4g} -> {:.4g} mm. The calibrated kinematics are written as a "
                  "LinuxCNC genhexkins setp block (compensation/kinematics.hal) and "
                  "loaded into the virtual machine's controller; the held-out poses "
                  "and the laser line are then measured again.",
                  data,
                  s.identifiability.rank,
                  s.identifiability.parameters,
                  s.identifiability.condition_number,
                  s.iterations,
                  s.before.rms,
                  s.after.rms),
      constrained_sets > 0
          ? "The tracker, registered to the table by six fiducial nests "
            "(measured-before/tracker-registration.csv), reads only the held-out poses. TCP "
            "error: a held-out tracker reading in the machine frame minus the commanded target "
            "position."
          : "The tracker is registered to the table by six fiducial nests "
            "(measured-before/tracker-registration.csv), so its readings are in the "
            "machine frame and all 42 parameters, the base placement included, are "
            "identifiable. TCP error: a held-out tracker reading in the machine frame "
            "minus the commanded target position."};
  if (constrained_sets > 0)
    out.push_back(
        "The dial gauges see only the platform's height and tilt over the table: the fit holds "
        "the geometry near the machine file (a prior, step key prior_sigma, default 5 mm; "
        "docs/calibration.md \"Weakly identified directions\"), corrects the motion the paper "
        "reports (the x positioning "
        "over 540 mm), and leaves the TCP error across the work volume, which only a tracker's "
        "full poses correct (the campaign's tracker step).");
  const simulation::GeometryEnvironment& g = scenario.campaign.environment.geometry;
  if (g.enabled)
    out.push_back(fmt::format(
        "Unmodelled geometry (docs/simulation-errors.md): the true struts' ball screws have lead "
        "errors (slope within ±{:g} µm/m, a {:g} µm wave over {:g} mm, {:g} µm per {:g} mm "
        "revolution) and the platform U-joints axis offsets within ±{:g} µm. No parameter of the "
        "42 represents them: part of the residual RMS after calibration ({:.4g} mm) is this "
        "remainder, which more poses do not remove, and it limits the held-out error after "
        "calibration (docs/simulation-errors.md gives each term's share at the realistic "
        "magnitudes).",
        g.lead_progressive * 1e6,
        g.lead_wave_mm * 1e3,
        g.lead_wave_length_mm,
        g.lead_periodic_mm * 1e3,
        g.screw_lead_mm,
        g.joint_axis_offset_mm * 1e3,
        s.after.rms));
  return out;
}

/// A TCP error map: target positions in the xy plane, coloured by |error| (mm).
Json tcpMap(const std::string& id,
            const std::string& title,
            const std::string& label,
            const TcpErrors& e) {
  Json p = plot(id, title, "scatter", "x (mm)", "y (mm)");
  addSeries(p, label, e.x, e.y);
  Json v = Json::array();
  for (double d : e.error) v.push_back(cell(d, 5));
  p["series"][0]["value"] = std::move(v);
  return p;
}

/// The positioning error along `linear` (mean of runs), before and after.
Json positioningPlot(const StepContext& ctx,
                     const std::string& id,
                     const std::string& linear,
                     const LineData& before,
                     const LineData& after) {
  std::vector<double> tb, mb, ta, ma;
  meanReadings(before.runs(linear, ctx.source), tb, mb);
  meanReadings(after.runs(linear, ctx.source), ta, ma);
  for (std::size_t i = 0; i < tb.size(); ++i) mb[i] -= tb[i];
  for (std::size_t i = 0; i < ta.size(); ++i) ma[i] -= ta[i];
  Json p = plot(id,
                fmt::format("Positioning error along {} (mean of runs)", linear),
                "line",
                "target (mm)",
                "deviation (mm)");
  addSeries(p, "before", tb, mb);
  addSeries(p, "after", ta, ma);
  return p;
}

/// The identifiability and uncertainty table of the calibration.
Json identifiabilityTable(const cal::HexapodCalibrationSummary& s) {
  Json id = table("Identifiability and uncertainty", {"quantity", "value"});
  id["rows"].push_back({"free parameters", s.identifiability.parameters});
  id["rows"].push_back({"identifiable combinations (rank)", s.identifiability.rank});
  id["rows"].push_back(
      {"condition number (scaled Jacobian)", cell(s.identifiability.condition_number)});
  id["rows"].push_back({"residual σ (mm)", cell(s.sigma)});
  id["rows"].push_back({"largest parameter σ (mm)", cell(s.standard_deviation.maxCoeff())});
  std::vector<double> v(s.standard_deviation.data(),
                        s.standard_deviation.data() + s.standard_deviation.size());
  std::nth_element(v.begin(), v.begin() + static_cast<long>(v.size() / 2), v.end());
  id["rows"].push_back({"median parameter σ (mm)", cell(v[v.size() / 2])});
  return id;
}

/// The parameters: nominal, estimated, true (simulation) and σ.
Json parameterTable(const simulation::HexapodVirtualMachine& vm,
                    const cal::HexapodCalibrationSummary& s) {
  const cal::HexapodParameterVector truth = cal::hexapodParameters(vm.truth());
  const cal::HexapodParameterVector nominal = cal::hexapodParameters(vm.nominal());
  Json par = table("Parameters: nominal, estimated, true (simulation), σ (mm)",
                   {"parameter", "nominal", "estimate", "truth", "σ"});
  for (int i = 0; i < static_cast<int>(nominal.size()); ++i)
    par["rows"].push_back({cal::hexapodParameterName(i),
                           cell(nominal[i], 7),
                           cell(s.parameters[i], 7),
                           cell(truth[i], 7),
                           cell(s.standard_deviation[i], 3)});
  return par;
}

}  // namespace

Json hexapodSection(const StepContext& ctx, const StepOutcome& out, const HexapodSectionData& d) {
  Json sec = section(
      out.id, out.title, paragraphs(d.scenario, d.seed, d.poses, d.constrained_sets, d.summary));
  sec["plots"] = Json::array(
      {tcpMap(out.id + "-tcp-before",
              "TCP error map before calibration: |error| (mm) at the held-out poses",
              "|error| before (mm)",
              d.tcp_before),
       tcpMap(out.id + "-tcp-after",
              "TCP error map after calibration: |error| (mm) at the held-out poses",
              "|error| after (mm)",
              d.tcp_after),
       positioningPlot(
           ctx, out.id + "-positioning", d.positioning, d.lines_before, d.lines_after)});
  sec["tables"] = Json::array({identifiabilityTable(d.summary), parameterTable(d.vm, d.summary)});
  if (d.uncertainty != nullptr) sec["tables"].push_back(budgetTable(*d.uncertainty));
  return sec;
}

}  // namespace pkm::workflow::campaign::detail
