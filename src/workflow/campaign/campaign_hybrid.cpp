// Campaign step "hybrid-squareness" (MXT700S parallelism paper): the MXT700S-like hybrid machine's
// parallelism and face diagonals measured with a laser interferometer, the four squareness errors
// estimated (§3), compensated by the PKM base-frame rotation and the X2 travel correction (§3.3)
// plus LinuxCNC axis tables for X2, Y2 and PZ, and measured again (docs/campaign.md).
#include <fmt/format.h>

#include <cmath>
#include <tuple>
#include <utility>

#include "campaign_hybrid_detail.hpp"
#include "campaign_steps.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/metrology/parallelism.hpp"
#include "pkm/simulation/compensated_machine.hpp"
#include "pkm/simulation/hybrid_virtual_machine.hpp"

namespace pkm::workflow::campaign {

namespace sim = pkm::simulation;
namespace met = pkm::metrology;

namespace {

using Analysis = detail::HybridAnalysis;

std::vector<double> column(const std::vector<double>& v, double scale) {
  std::vector<double> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = v[i] * scale;
  return out;
}

/// The estimated squareness errors into the result store.
void recordSquareness(StepOutcome& out, const kinematics::HybridSquareness& e) {
  out.record.results.push_back({"squareness.szX2", "estimate", e.sz_x2, "rad"});
  out.record.results.push_back({"squareness.sxP", "estimate", e.sx_p, "rad"});
  out.record.results.push_back({"squareness.syP", "estimate", e.sy_p, "rad"});
  out.record.results.push_back({"squareness.szP", "estimate", e.sz_p, "rad"});
}

/// The summary rows of the measured files: the figures as measured, no "after".
void addMeasuredRows(StepOutcome& out, const Analysis& ab, const met::UncertaintySources& u) {
  const std::pair<const char*, double> figures[] = {
      {"parallelism Y2-PY, horizontal", std::abs(ab.horizontal.parallelism)},
      {"parallelism Y2-PY, vertical", std::abs(ab.vertical.parallelism)},
      {"face diagonal X2-Y2 error (ISO 230-2 E)", ab.diag_xy.E},
      {"face diagonal X2-PZ error (ISO 230-2 E)", ab.diag_xz.E}};
  for (const auto& [quantity, value] : figures)
    out.rows.push_back({quantity, "mm", value, std::nan(""), std::nullopt, "", "as measured"});
  const double U[] = {
      ab.horizontal_U, ab.vertical_U, iso230_2U(ab.diag_xy, "E", u), iso230_2U(ab.diag_xz, "E", u)};
  for (std::size_t k = 0; k < 4; ++k) out.rows[out.rows.size() - 4 + k].before_U = U[k];
}

/// The step on measured laser files ("data": {"folder": DIR}): analysis and compensation files,
/// no re-measurement (docs/campaign.md, "Measured data").
StepOutcome fromFiles(const StepContext& ctx) {
  const std::string folder = dataFolder(ctx);
  const io::ExechonMachine machine =
      io::loadExechonMachine(ctx.spec.value("machine", std::string("default")));
  if (!machine.hybrid)
    throw IoError(
        fmt::format("{}: machine '{}' is not a hybrid machine", ctx.source, machine.model.name));
  StepOutcome out;
  out.id = ctx.spec.value("id", std::string("seed000"));
  out.title = fmt::format("Hybrid machine {}: parallelism and squareness from measured files",
                          machine.hybrid->name);
  out.record.machine = machine.hybrid->name;
  out.record.machine_type = "hybrid";
  const LineFiles files = readLineFolder(ctx, folder);
  out.record.source = fmt::format("{} files", files.paths.size());
  for (const std::string& p : files.paths)
    out.record.measurements.push_back({std::filesystem::path(p).stem().string(), "laser", p, 0});
  ctx.progress(fmt::format("analyse: {} laser files", files.paths.size()));
  const Analysis ab = detail::analyseHybrid(files.data, ctx.source, ctx.sources);
  (void)detail::compensateHybrid(ctx, out, files.data, *machine.hybrid, ab);
  addMeasuredRows(out, ab, ab.sources);
  const kinematics::HybridSquareness& e = ab.squareness;
  recordSquareness(out, e);
  Json sec = section(out.id,
                     out.title,
                     {fmt::format("Measured files: {} in {}. The compensation is written to "
                                  "compensation/; measuring again with it loaded is the machine's "
                                  "next campaign.",
                                  files.paths.size(),
                                  folder)});
  Json sqt = table("Squareness errors (mrad)", {"error", "estimate", "seed 000"});
  sqt["rows"].push_back({"szX2", cell(e.sz_x2 * 1e3), "-0.034"});
  sqt["rows"].push_back({"sxP", cell(e.sx_p * 1e3), "-14.74"});
  sqt["rows"].push_back({"syP", cell(e.sy_p * 1e3), "4.35"});
  sqt["rows"].push_back({"szP", cell(e.sz_p * 1e3), "-2.85"});
  sec["tables"].push_back(sqt);
  out.section = std::move(sec);
  return out;
}

/// The parallelism rows over the paper's 50 mm, when both passes measured them (MXT700S parallelism
/// paper, Table 3).
void add50mmRows(StepOutcome& out,
                 const Analysis& ab,
                 const Analysis& aa,
                 double target,
                 const std::string& noise) {
  using Figure = std::tuple<const char*,
                            const char*,
                            const std::optional<met::ParallelismResult>*,
                            const std::optional<met::ParallelismResult>*,
                            double,
                            double>;
  const Figure figures[] = {{"parallelism Y2-PY, horizontal (50 mm)",
                             "0.134 -> 0.015 mm",
                             &ab.horizontal_50,
                             &aa.horizontal_50,
                             ab.horizontal_50_U,
                             aa.horizontal_50_U},
                            {"parallelism Y2-PY, vertical (50 mm)",
                             "0.735 -> 0.022 mm",
                             &ab.vertical_50,
                             &aa.vertical_50,
                             ab.vertical_50_U,
                             aa.vertical_50_U}};
  for (const auto& [quantity, paper, b, a, ub, ua] : figures) {
    if (!*b || !*a) continue;
    out.rows.push_back({quantity,
                        "mm",
                        std::abs((*b)->parallelism),
                        std::abs((*a)->parallelism),
                        target,
                        paper,
                        noise});
    out.rows.back().before_U = ub;
    out.rows.back().after_U = ua;
  }
}

/// The summary rows of the simulated step: before and after compensation.
void addRows(const StepContext& ctx,
             StepOutcome& out,
             const io::Scenario& scenario,
             const LineData& before,
             const Analysis& ab,
             const Analysis& aa) {
  // The MXT700S parallelism paper (Table 3, §4): parallelism 0.134 -> 0.015 mm (x) and
  // 0.735 -> 0.022 mm (z) over 50 mm of the PKM's y travel (its optics' range); face diagonals
  // X2-PZ 1.216 -> 0.082 mm and X2-Y2 0.082 -> 0.011 mm. The 300 mm rows have no paper figure.
  const double parallelism_target = stepTarget(scenario, 0.010, 0.030);
  const double xy_target = stepTarget(scenario, 0.02, 0.011);
  const double xz_target = stepTarget(scenario, 0.02, 0.082);
  const sim::LineSetup& st = before.setup("straightness-py-h", ctx.source);
  const sim::LineSetup& li = before.setup("diagonal-x2-y2", ctx.source);
  const std::string st_noise = fmt::format("laser straightness {:g} µm", st.noise.sigma * 1e3);
  const std::string li_noise =
      fmt::format("laser {:g} µm + {:g} ppm", li.noise.sigma * 1e3, li.noise.sigma_ppm);
  out.rows.push_back({"parallelism Y2-PY, horizontal (300 mm)",
                      "mm",
                      std::abs(ab.horizontal.parallelism),
                      std::abs(aa.horizontal.parallelism),
                      parallelism_target,
                      "",
                      st_noise});
  out.rows.push_back({"parallelism Y2-PY, vertical (300 mm)",
                      "mm",
                      std::abs(ab.vertical.parallelism),
                      std::abs(aa.vertical.parallelism),
                      parallelism_target,
                      "",
                      st_noise});
  out.rows.push_back({"face diagonal X2-Y2 error (ISO 230-2 E)",
                      "mm",
                      ab.diag_xy.E,
                      aa.diag_xy.E,
                      xy_target,
                      "0.082 -> 0.011 mm",
                      li_noise});
  out.rows.push_back({"face diagonal X2-PZ error (ISO 230-2 E)",
                      "mm",
                      ab.diag_xz.E,
                      aa.diag_xz.E,
                      xz_target,
                      "1.216 -> 0.082 mm",
                      li_noise});
  const std::pair<double, double> U[] = {
      {ab.horizontal_U, aa.horizontal_U},
      {ab.vertical_U, aa.vertical_U},
      {iso230_2U(ab.diag_xy, "E", ab.sources), iso230_2U(aa.diag_xy, "E", aa.sources)},
      {iso230_2U(ab.diag_xz, "E", ab.sources), iso230_2U(aa.diag_xz, "E", aa.sources)}};
  for (std::size_t k = 0; k < 4; ++k) {
    SummaryRow& row = out.rows[out.rows.size() - 4 + k];
    std::tie(row.before_U, row.after_U) = U[k];
  }
  const std::size_t first = out.rows.size() - 4;
  out.rows[first].after_limit = aa.horizontal_limit;
  out.rows[first + 1].after_limit = aa.vertical_limit;
  setIso230_2AfterU(out.rows[first + 2], aa.diag_xy, "E", aa.sources);
  setIso230_2AfterU(out.rows[first + 3], aa.diag_xz, "E", aa.sources);
  add50mmRows(out, ab, aa, parallelism_target, st_noise);
}

/// The report section of the simulated step, without its plots.
Json simulatedSection(const StepOutcome& out,
                      const io::Scenario& scenario,
                      std::uint64_t seed,
                      const kinematics::HybridSquareness& e,
                      const kinematics::HybridSquareness& t) {
  Json sec =
      section(out.id,
              out.title,
              {fmt::format("Scenario {} (seed {}): {}",
                           scenario.campaign.name,
                           seed,
                           scenario.campaign.description),
               "Analysis: parallelism of the PKM's Y to Y2 from the straightness runs along one "
               "beam (seed 000 §3.1), szX2 and syP from the X2-Y2 and X2-PZ face diagonals "
               "with the measured positioning and straightness PDGEs removed (§3.2), sxP and "
               "szP from the slope differences (eq. 11 with its second-order terms, "
               "parallelism.hpp). Compensation: the PKM base-frame "
               "rotation and the X2-travel correction (§3.3, compensation/pkm-base-frame.txt) "
               "and LinuxCNC COMP_FILE type 1 tables of X2, Y2 and PZ from the positioning "
               "runs (compensation/*.comp), applied in the virtual machine's controller."});
  Json sqt = table("Squareness errors (mrad): estimated vs injected",
                   {"error", "estimate", "truth", "seed 000"});
  sqt["rows"].push_back({"szX2", cell(e.sz_x2 * 1e3), cell(t.sz_x2 * 1e3), "-0.034"});
  sqt["rows"].push_back({"sxP", cell(e.sx_p * 1e3), cell(t.sx_p * 1e3), "-14.74"});
  sqt["rows"].push_back({"syP", cell(e.sy_p * 1e3), cell(t.sy_p * 1e3), "4.35"});
  sqt["rows"].push_back({"szP", cell(e.sz_p * 1e3), cell(t.sz_p * 1e3), "-2.85"});
  sec["tables"].push_back(sqt);
  return sec;
}

/// The line measurements and analyses before and after compensation, for the plots.
struct Passes {
  const std::string& id;      ///< the step's id (plot id prefix)
  const std::string& source;  ///< for messages
  const LineData& before;
  const LineData& after;
  const Analysis& ab;
  const Analysis& aa;
};

/// The parallelism error profile of straightness run `name`, before and after.
Json parallelPlot(const Passes& d,
                  const std::string& id,
                  const std::string& title,
                  const std::string& name,
                  const met::ParallelismResult& b,
                  const met::ParallelismResult& a) {
  std::vector<double> s, m;
  meanReadings(d.before.runs(name, d.source), s, m);
  Json p = plot(d.id + id, title, "line", "PKM y travel s (mm)", "parallelism error profile (µm)");
  addSeries(p, "before", s, column(b.deviations, 1e3));
  meanReadings(d.after.runs(name, d.source), s, m);
  addSeries(p, "after", s, column(a.deviations, 1e3));
  return p;
}

/// The after profiles alone, on their own scale.
Json parallelAfterPlot(const Passes& d) {
  Json p = plot(d.id + "-par-after",
                "Parallelism of PY to Y2 after compensation",
                "line",
                "PKM y travel s (mm)",
                "parallelism error profile (µm)");
  std::vector<double> s, m;
  meanReadings(d.after.runs("straightness-py-h", d.source), s, m);
  addSeries(p, "after, horizontal", s, column(d.aa.horizontal.deviations, 1e3));
  meanReadings(d.after.runs("straightness-py-v", d.source), s, m);
  addSeries(p, "after, vertical", s, column(d.aa.vertical.deviations, 1e3));
  return p;
}

/// The deviation along face diagonal `name` (µm), before and after.
Json diagonalPlot(const Passes& d,
                  const std::string& id,
                  const std::string& title,
                  const std::string& name) {
  Json p = plot(d.id + id, title, "line", "position along the diagonal (mm)", "deviation (µm)");
  for (const auto& [data, label] : {std::pair{&d.before, "before"}, std::pair{&d.after, "after"}}) {
    std::vector<double> s, m;
    meanReadings(data->runs(name, d.source), s, m);
    for (std::size_t i = 0; i < s.size(); ++i) m[i] = (m[i] - s[i]) * 1e3;
    addSeries(p, label, s, m);
  }
  return p;
}

/// The plots of the simulated step.
void addPlots(Json& sec, const Passes& d) {
  sec["plots"].push_back(parallelPlot(d,
                                      "-par-h",
                                      "Parallelism of PY to Y2, horizontal (seed 000 Fig. 10)",
                                      "straightness-py-h",
                                      d.ab.horizontal,
                                      d.aa.horizontal));
  sec["plots"].push_back(parallelPlot(d,
                                      "-par-v",
                                      "Parallelism of PY to Y2, vertical (seed 000 Fig. 10)",
                                      "straightness-py-v",
                                      d.ab.vertical,
                                      d.aa.vertical));
  sec["plots"].push_back(parallelAfterPlot(d));
  sec["plots"].push_back(
      diagonalPlot(d, "-diag-xy", "Face diagonal X2-Y2 (seed 000 Fig. 11)", "diagonal-x2-y2"));
  sec["plots"].push_back(
      diagonalPlot(d, "-diag-xz", "Face diagonal X2-PZ (seed 000 Fig. 11)", "diagonal-x2-pz"));
}

}  // namespace

StepOutcome runHybridSquarenessStep(const StepContext& ctx) {
  if (ctx.spec.contains("data")) return fromFiles(ctx);
  std::uint64_t seed = 0;
  io::Scenario scenario = stepScenario(ctx, seed);
  const auto vm = scenarioMachine<sim::HybridVirtualMachine>(ctx, scenario, "hybrid-machine");
  const std::string& src = ctx.source;
  StepOutcome out;
  out.id = ctx.spec.value("id", std::string("seed000"));
  out.title = "Hybrid machine: parallelism and squareness (seed 000)";
  out.record.machine = vm->model().name;
  out.record.machine_type = "hybrid";
  out.record.source = scenario.source;

  ctx.progress("measure: straightness, positioning and face diagonals with the laser");
  const LineData before{sim::runCampaign(scenario.campaign, seed),
                        setupRecords(scenario.campaign.environment)};
  writeLineFiles(ctx, out, "measured-before", scenario, seed, before);
  ctx.progress("analyse: parallelism (seed 000 §3.1), face-diagonal squareness (§3.2), eq. 11");
  const Analysis ab = detail::analyseHybrid(before, src, ctx.sources);

  const std::shared_ptr<sim::CompensationChain> chain =
      detail::compensateHybrid(ctx, out, before, vm->model(), ab);

  ctx.progress("re-measure: the same lines through the compensating controller");
  io::Scenario again = remeasureScenario(scenario);
  again.campaign.machine = std::make_shared<sim::CompensatedMachine>(vm, chain);
  const LineData after{sim::runCampaign(again.campaign, remeasureSeed(seed)),
                       setupRecords(again.campaign.environment)};
  writeLineFiles(ctx, out, "measured-after", scenario, remeasureSeed(seed), after);
  const Analysis aa = detail::analyseHybrid(after, src, ctx.sources);

  addRows(ctx, out, scenario, before, ab, aa);
  recordSquareness(out, ab.squareness);
  Json sec = simulatedSection(out, scenario, seed, ab.squareness, vm->errors().squareness);
  addPlots(sec, {out.id, src, before, after, ab, aa});
  out.section = std::move(sec);
  return out;
}

}  // namespace pkm::workflow::campaign
