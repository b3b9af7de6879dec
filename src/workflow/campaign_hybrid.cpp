// Campaign step "hybrid-squareness" (seed 000): the MXT700S-like hybrid machine's parallelism and
// face diagonals measured with a laser interferometer, the four squareness errors estimated
// (seed 000 §3), compensated by the PKM base-frame rotation and the X2 travel correction
// (§3.3) plus LinuxCNC axis tables for X2, Y2 and PZ, and measured again (docs/campaign.md).
#include <fmt/format.h>

#include <cmath>

#include "campaign_compensation.hpp"
#include "campaign_steps.hpp"
#include "pkm/compensation/axis_table.hpp"
#include "pkm/compensation/hybrid_squareness.hpp"
#include "pkm/compensation/linuxcnc_comp.hpp"
#include "pkm/compensation/siemens_comp.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/metrology/face_diagonal.hpp"
#include "pkm/metrology/parallelism.hpp"
#include "pkm/simulation/compensated_machine.hpp"
#include "pkm/simulation/hybrid_virtual_machine.hpp"

namespace pkm::workflow::campaign {

namespace sim = pkm::simulation;
namespace met = pkm::metrology;
namespace comp = pkm::compensation;

namespace {

/// Axis position of line coordinate s: start[axis] + s·direction[axis].
double axisPosition(const sim::LineSetup& setup, int axis, double s) {
  return setup.line.start[axis] + s * setup.line.direction[axis];
}

/// A straightness run (mean per target) as a BeamRun.
met::BeamRun beam(const LineData& d, const std::string& name, int sign, const std::string& source) {
  met::BeamRun b;
  meanReadings(d.runs(name, source), b.positions, b.deviations);
  b.beam_sign = sign;
  return b;
}

/// A PDGE table over axis `axis` from a linear run (deviation = reading − target) or, when
/// `straightness`, from a straightness run with its least-squares line removed.
met::PdgeTerm pdge(const LineData& d,
                   const std::string& name,
                   int axis,
                   int argument,
                   int component,
                   bool straightness,
                   const std::string& source) {
  std::vector<double> s, m;
  meanReadings(d.runs(name, source), s, m);
  const sim::LineSetup& setup = d.setup(name, source);
  std::vector<double> pos(s.size());
  for (std::size_t i = 0; i < s.size(); ++i) pos[i] = axisPosition(setup, axis, s[i]);
  Eigen::MatrixXd v(static_cast<Eigen::Index>(s.size()), 1);
  if (straightness) {
    const met::ReferenceLine l = met::leastSquaresLine(s, m);
    for (std::size_t i = 0; i < s.size(); ++i)
      v(static_cast<Eigen::Index>(i), 0) = m[i] - (l.slope * s[i] + l.intercept);
  } else {
    for (std::size_t i = 0; i < s.size(); ++i) v(static_cast<Eigen::Index>(i), 0) = m[i] - s[i];
  }
  if (pos.size() > 1 && pos.front() > pos.back()) {
    std::reverse(pos.begin(), pos.end());
    v = v.colwise().reverse().eval();
  }
  met::PdgeTerm t{geometry::ErrorTable1d(pos, v), argument, component, 1.0, 0.0};
  return t;
}

/// A face diagonal of axes a, b (indices) from a linear run, mean per target.
met::FaceDiagonal diagonal(
    const LineData& d, const std::string& name, int a, int b, const std::string& source) {
  std::vector<double> s, m;
  meanReadings(d.runs(name, source), s, m);
  const sim::LineSetup& setup = d.setup(name, source);
  met::FaceDiagonal f;
  f.start_a = setup.line.start[a];
  f.start_b = setup.line.start[b];
  const double s0 = s.front();
  for (std::size_t i = 0; i < s.size(); ++i)
    f.points.push_back({(s[i] - s0) * setup.line.direction[a],
                        (s[i] - s0) * setup.line.direction[b],
                        (m[i] - m.front()) - (s[i] - s0)});
  return f;
}

struct Analysis {
  met::ParallelismResult horizontal, vertical;
  kinematics::HybridSquareness squareness;
  met::Iso230_2Result diag_xy, diag_xz;
};

Analysis analyse(const LineData& d, const std::string& src) {
  Analysis a;
  a.horizontal = met::evaluateParallelism(beam(d, "straightness-y2-h", -1, src),
                                          beam(d, "straightness-py-h", 1, src));
  a.vertical = met::evaluateParallelism(beam(d, "straightness-y2-v", -1, src),
                                        beam(d, "straightness-py-v", 1, src));
  met::FaceDiagonalOptions xy_options;
  xy_options.second_moves_work = true;
  const std::vector<met::FaceDiagonal> xy = {diagonal(d, "diagonal-x2-y2", 0, 1, src)};
  const std::vector<met::PdgeTerm> xy_pdge = {pdge(d, "linear-x2", 0, 0, 0, false, src),
                                              pdge(d, "linear-y2", 1, 1, 1, false, src),
                                              pdge(d, "straightness-y2-h", 1, 1, 0, true, src)};
  a.squareness.sz_x2 = met::fitFaceDiagonalSquareness(xy, xy_pdge, xy_options).squareness;
  const std::vector<met::FaceDiagonal> xz = {diagonal(d, "diagonal-x2-pz", 0, 4, src)};
  const std::vector<met::PdgeTerm> xz_pdge = {pdge(d, "linear-x2", 0, 0, 0, false, src),
                                              pdge(d, "linear-pz", 4, 1, 1, false, src),
                                              pdge(d, "straightness-x2-v", 0, 0, 1, true, src)};
  a.squareness.sy_p = met::fitFaceDiagonalSquareness(xz, xz_pdge).squareness;
  const met::PkmSquareness p = met::pkmSquarenessFromSlopes(a.horizontal.slope_difference,
                                                            a.vertical.slope_difference,
                                                            a.squareness.sz_x2,
                                                            a.squareness.sy_p);
  a.squareness.sx_p = p.sxP;
  a.squareness.sz_p = p.szP;
  a.diag_xy = iso230_2(d.runs("diagonal-x2-y2", src));
  a.diag_xz = iso230_2(d.runs("diagonal-x2-pz", src));
  return a;
}

std::vector<double> column(const std::vector<double>& v, double scale) {
  std::vector<double> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) out[i] = v[i] * scale;
  return out;
}

/// The hybrid machine's axes, in command order (HybridVirtualMachine::axisNames).
const std::vector<std::string> kAxes = {"x2", "y2", "xp", "yp", "zp"};

/// Writes the compensation of `ab` (base frame + X2 correction, the X2→yp cross table, the axis
/// tables of X2, Y2 and PZ) and returns it as the controller's command compensation.
std::shared_ptr<sim::CompensationChain> compensate(const StepContext& ctx,
                                                   StepOutcome& out,
                                                   const LineData& before,
                                                   const kinematics::HybridMachineModel& model,
                                                   const Analysis& ab) {
  // Compensation: squareness (base frame + X2 correction) and axis tables.
  const comp::HybridSquarenessCompensation sq =
      comp::hybridSquarenessCompensation(model, ab.squareness);
  auto chain = std::make_shared<sim::CompensationChain>();
  chain->add(std::make_shared<HybridSquarenessController>(sq));
  auto axis_comp = std::make_shared<AxisTableController>(5);
  writeAxisTables(
      ctx, out, before, {{"linear-x2", 0}, {"linear-y2", 1}, {"linear-pz", 4}}, kAxes, *axis_comp);
  chain->add(axis_comp);
  const std::string frame_text = fmt::format(
      "# PKM base-frame correction (seed 000 §3.3; docs/compensation.md)\n"
      "# squareness rad: szX2 {:.6e} sxP {:.6e} syP {:.6e} szP {:.6e}\n"
      "base_rpy_rad = {:.9e} {:.9e} {:.9e}\nbase_offset_mm = {:.6f} {:.6f} {:.6f}\n"
      "per_x2 = {:.9e} {:.9e} {:.9e}\n",
      ab.squareness.sz_x2,
      ab.squareness.sx_p,
      ab.squareness.sy_p,
      ab.squareness.sz_p,
      sq.base_rpy.x(),
      sq.base_rpy.y(),
      sq.base_rpy.z(),
      sq.base_offset.x(),
      sq.base_offset.y(),
      sq.base_offset.z(),
      sq.per_x2.x(),
      sq.per_x2.y(),
      sq.per_x2.z());
  ctx.writeCompensation(out, "pkm-base-frame", "compensation/pkm-base-frame.txt", frame_text);
  // The X2–Y2 squareness part (b₁, the PKM y correction per mm of X2) as a SINUMERIK cross-axis
  // table over the X2 travel: the error of yp is −b₁,y·x2 (docs/compensation.md, the CEC sign).
  {
    const kinematics::HybridStroke& x2 = model.x2_stroke;
    const double lo = std::isfinite(x2.min) ? x2.min : 0.0;
    const double hi =
        std::isfinite(x2.max) ? x2.max : before.setup("linear-x2", ctx.source).cycle.last;
    constexpr int kRows = 41;
    std::vector<double> pos(kRows), err(kRows);
    for (int k = 0; k < kRows; ++k) {
      pos[static_cast<std::size_t>(k)] = lo + (hi - lo) * k / (kRows - 1);
      err[static_cast<std::size_t>(k)] = -sq.per_x2.y() * pos[static_cast<std::size_t>(k)];
    }
    const std::string cec = comp::writeSiemensCec(
        comp::siemensCecFromTable(comp::crossTableFromPoints("x2", "yp", pos, err)));
    ctx.writeCompensation(out, "siemens-cec", "compensation/x2-yp.cec.spf", cec);
  }

  return chain;
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
  const Analysis ab = analyse(files.data, ctx.source);
  (void)compensate(ctx, out, files.data, *machine.hybrid, ab);
  const double nan = std::nan("");
  out.rows.push_back({"parallelism Y2-PY, horizontal",
                      "mm",
                      std::abs(ab.horizontal.parallelism),
                      nan,
                      std::nullopt,
                      "",
                      "as measured"});
  out.rows.push_back({"parallelism Y2-PY, vertical",
                      "mm",
                      std::abs(ab.vertical.parallelism),
                      nan,
                      std::nullopt,
                      "",
                      "as measured"});
  out.rows.push_back({"face diagonal X2-Y2 error (ISO 230-2 E)",
                      "mm",
                      ab.diag_xy.E,
                      nan,
                      std::nullopt,
                      "",
                      "as measured"});
  out.rows.push_back({"face diagonal X2-PZ error (ISO 230-2 E)",
                      "mm",
                      ab.diag_xz.E,
                      nan,
                      std::nullopt,
                      "",
                      "as measured"});
  const kinematics::HybridSquareness& e = ab.squareness;
  out.record.results.push_back({"squareness.szX2", "estimate", e.sz_x2, "rad"});
  out.record.results.push_back({"squareness.sxP", "estimate", e.sx_p, "rad"});
  out.record.results.push_back({"squareness.syP", "estimate", e.sy_p, "rad"});
  out.record.results.push_back({"squareness.szP", "estimate", e.sz_p, "rad"});
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
  const LineData before{sim::runCampaign(scenario.campaign, seed)};
  writeLineFiles(ctx, out, "measured-before", scenario, seed, before);
  ctx.progress("analyse: parallelism (seed 000 §3.1), face-diagonal squareness (§3.2), eq. 11");
  const Analysis ab = analyse(before, src);

  const std::shared_ptr<sim::CompensationChain> chain =
      compensate(ctx, out, before, vm->model(), ab);

  ctx.progress("re-measure: the same lines through the compensating controller");
  io::Scenario again = scenario;
  again.campaign.machine = std::make_shared<sim::CompensatedMachine>(vm, chain);
  const LineData after{sim::runCampaign(again.campaign, remeasureSeed(seed))};
  writeLineFiles(ctx, out, "measured-after", scenario, remeasureSeed(seed), after);
  const Analysis aa = analyse(after, src);

  const sim::LineSetup& st = before.setup("straightness-py-h", src);
  const sim::LineSetup& li = before.setup("diagonal-x2-y2", src);
  const std::string st_noise = fmt::format("laser straightness {:g} µm", st.noise.sigma * 1e3);
  const std::string li_noise =
      fmt::format("laser {:g} µm + {:g} ppm", li.noise.sigma * 1e3, li.noise.sigma_ppm);
  out.rows.push_back({"parallelism Y2-PY, horizontal (300 mm)",
                      "mm",
                      std::abs(ab.horizontal.parallelism),
                      std::abs(aa.horizontal.parallelism),
                      0.010,
                      "0.735 -> 0.022 mm",
                      st_noise});
  out.rows.push_back({"parallelism Y2-PY, vertical (300 mm)",
                      "mm",
                      std::abs(ab.vertical.parallelism),
                      std::abs(aa.vertical.parallelism),
                      0.010,
                      "",
                      st_noise});
  out.rows.push_back({"face diagonal X2-Y2 error (ISO 230-2 E)",
                      "mm",
                      ab.diag_xy.E,
                      aa.diag_xy.E,
                      0.02,
                      "-> 0.082 mm",
                      li_noise});
  out.rows.push_back({"face diagonal X2-PZ error (ISO 230-2 E)",
                      "mm",
                      ab.diag_xz.E,
                      aa.diag_xz.E,
                      0.02,
                      "",
                      li_noise});
  const kinematics::HybridSquareness& e = ab.squareness;
  const kinematics::HybridSquareness& t = vm->errors().squareness;
  out.record.results.push_back({"squareness.szX2", "estimate", e.sz_x2, "rad"});
  out.record.results.push_back({"squareness.sxP", "estimate", e.sx_p, "rad"});
  out.record.results.push_back({"squareness.syP", "estimate", e.sy_p, "rad"});
  out.record.results.push_back({"squareness.szP", "estimate", e.sz_p, "rad"});

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
  auto parallelPlot = [&](const std::string& id,
                          const std::string& title,
                          const std::string& name,
                          const met::ParallelismResult& b,
                          const met::ParallelismResult& a) {
    std::vector<double> s, m;
    meanReadings(before.runs(name, src), s, m);
    Json p =
        plot(out.id + id, title, "line", "PKM y travel s (mm)", "parallelism error profile (µm)");
    addSeries(p, "before", s, column(b.deviations, 1e3));
    meanReadings(after.runs(name, src), s, m);
    addSeries(p, "after", s, column(a.deviations, 1e3));
    return p;
  };
  sec["plots"].push_back(parallelPlot("-par-h",
                                      "Parallelism of PY to Y2, horizontal (seed 000 Fig. 10)",
                                      "straightness-py-h",
                                      ab.horizontal,
                                      aa.horizontal));
  sec["plots"].push_back(parallelPlot("-par-v",
                                      "Parallelism of PY to Y2, vertical (seed 000 Fig. 10)",
                                      "straightness-py-v",
                                      ab.vertical,
                                      aa.vertical));
  {
    // The after profiles alone, on their own scale.
    Json p = plot(out.id + "-par-after",
                  "Parallelism of PY to Y2 after compensation",
                  "line",
                  "PKM y travel s (mm)",
                  "parallelism error profile (µm)");
    std::vector<double> s, m;
    meanReadings(after.runs("straightness-py-h", src), s, m);
    addSeries(p, "after, horizontal", s, column(aa.horizontal.deviations, 1e3));
    meanReadings(after.runs("straightness-py-v", src), s, m);
    addSeries(p, "after, vertical", s, column(aa.vertical.deviations, 1e3));
    sec["plots"].push_back(std::move(p));
  }
  auto diagPlot = [&](const std::string& id, const std::string& title, const std::string& name) {
    Json p = plot(out.id + id, title, "line", "position along the diagonal (mm)", "deviation (µm)");
    for (const auto* d : {&before, &after}) {
      std::vector<double> s, m;
      meanReadings(d->runs(name, src), s, m);
      for (std::size_t i = 0; i < s.size(); ++i) m[i] = (m[i] - s[i]) * 1e3;
      addSeries(p, d == &before ? "before" : "after", s, m);
    }
    return p;
  };
  sec["plots"].push_back(
      diagPlot("-diag-xy", "Face diagonal X2-Y2 (seed 000 Fig. 11)", "diagonal-x2-y2"));
  sec["plots"].push_back(
      diagPlot("-diag-xz", "Face diagonal X2-PZ (seed 000 Fig. 11)", "diagonal-x2-pz"));
  out.section = std::move(sec);
  return out;
}

}  // namespace pkm::workflow::campaign
