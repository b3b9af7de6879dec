// Analysis and compensation of the campaign step "hybrid-squareness" (MXT700S parallelism paper,
// §3): the Y2-PY parallelism, the face-diagonal squareness and the four squareness errors from the
// laser lines; the PKM base-frame correction, the X2 cross table and the axis tables written and
// returned as the controller's compensation (docs/campaign.md).
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <utility>

#include "campaign_compensation.hpp"
#include "campaign_hybrid_detail.hpp"
#include "campaign_steps.hpp"
#include "pkm/compensation/axis_table.hpp"
#include "pkm/compensation/hybrid_squareness.hpp"
#include "pkm/compensation/siemens_comp.hpp"
#include "pkm/metrology/face_diagonal.hpp"
#include "pkm/metrology/parallelism.hpp"
#include "pkm/metrology/profile_uncertainty.hpp"

namespace pkm::workflow::campaign::detail {

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

/// The hybrid machine's axes, in command order (HybridVirtualMachine::axisNames).
const std::vector<std::string> kAxes = {"x2", "y2", "xp", "yp", "zp"};

/// Writes the PKM base-frame correction `sq` of the squareness errors `e`.
void writeBaseFrame(const StepContext& ctx,
                    StepOutcome& out,
                    const kinematics::HybridSquareness& e,
                    const comp::HybridSquarenessCompensation& sq) {
  const std::string frame_text = fmt::format(
      "# PKM base-frame correction (seed 000 §3.3; docs/compensation.md)\n"
      "# squareness rad: szX2 {:.6e} sxP {:.6e} syP {:.6e} szP {:.6e}\n"
      "base_rpy_rad = {:.9e} {:.9e} {:.9e}\nbase_offset_mm = {:.6f} {:.6f} {:.6f}\n"
      "per_x2 = {:.9e} {:.9e} {:.9e}\n",
      e.sz_x2,
      e.sx_p,
      e.sy_p,
      e.sz_p,
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
}

/// Writes the X2–Y2 squareness part (b₁, the PKM y correction per mm of X2) as a SINUMERIK
/// cross-axis table over the X2 travel: the error of yp is −b₁,y·x2 (docs/compensation.md, the CEC
/// sign).
void writeCrossTable(const StepContext& ctx,
                     StepOutcome& out,
                     const LineData& before,
                     const kinematics::HybridMachineModel& model,
                     const comp::HybridSquarenessCompensation& sq) {
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

}  // namespace

namespace {

/// U (k = 2, mm) of a parallelism from its two runs with the instruments of `sources`; NaN when a
/// run has fewer than 3 points.
/// The parallelism's U (k = 2) and its largest contributors.
std::pair<double, std::string> parallelismU(const met::ParallelismResult& r,
                                            const met::BeamRun& reference,
                                            const met::BeamRun& axis,
                                            const met::UncertaintySources& sources) {
  if (reference.positions.size() < 3 || axis.positions.size() < 3) return {std::nan(""), ""};
  const met::UncertaintyBudget b = met::parallelismUncertainty(
      r.parallelism,
      {reference.positions, r.reference_straightness.residuals, reference.deviations},
      {axis.positions, r.axis_straightness.residuals, axis.deviations},
      sources);
  return {b.expandedUncertainty(), campaign::largestContributors(b)};
}

}  // namespace

HybridAnalysis analyseHybrid(const LineData& d,
                             const std::string& src,
                             const met::UncertaintySources& base) {
  HybridAnalysis a;
  a.sources = sourcesAt(base, d);
  const met::UncertaintySources& sources = a.sources;
  const met::BeamRun y2h = beam(d, "straightness-y2-h", -1, src);
  const met::BeamRun pyh = beam(d, "straightness-py-h", 1, src);
  const met::BeamRun y2v = beam(d, "straightness-y2-v", -1, src);
  const met::BeamRun pyv = beam(d, "straightness-py-v", 1, src);
  a.horizontal = met::evaluateParallelism(y2h, pyh);
  a.vertical = met::evaluateParallelism(y2v, pyv);
  std::tie(a.horizontal_U, a.horizontal_limit) = parallelismU(a.horizontal, y2h, pyh, sources);
  std::tie(a.vertical_U, a.vertical_limit) = parallelismU(a.vertical, y2v, pyv, sources);
  if (d.has("straightness-y2-h-50") && d.has("straightness-py-h-50")) {
    const met::BeamRun r = beam(d, "straightness-y2-h-50", -1, src);
    const met::BeamRun x = beam(d, "straightness-py-h-50", 1, src);
    a.horizontal_50 = met::evaluateParallelism(r, x);
    a.horizontal_50_U = parallelismU(*a.horizontal_50, r, x, sources).first;
  }
  if (d.has("straightness-y2-v-50") && d.has("straightness-py-v-50")) {
    const met::BeamRun r = beam(d, "straightness-y2-v-50", -1, src);
    const met::BeamRun x = beam(d, "straightness-py-v-50", 1, src);
    a.vertical_50 = met::evaluateParallelism(r, x);
    a.vertical_50_U = parallelismU(*a.vertical_50, r, x, sources).first;
  }
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

std::shared_ptr<sim::CompensationChain> compensateHybrid(
    const StepContext& ctx,
    StepOutcome& out,
    const LineData& before,
    const kinematics::HybridMachineModel& model,
    const HybridAnalysis& ab) {
  // Compensation: squareness (base frame + X2 correction) and axis tables.
  const comp::HybridSquarenessCompensation sq =
      comp::hybridSquarenessCompensation(model, ab.squareness);
  auto chain = std::make_shared<sim::CompensationChain>();
  chain->add(std::make_shared<HybridSquarenessController>(sq));
  auto axis_comp = std::make_shared<AxisTableController>(5);
  writeAxisTables(
      ctx, out, before, {{"linear-x2", 0}, {"linear-y2", 1}, {"linear-pz", 4}}, kAxes, *axis_comp);
  chain->add(axis_comp);
  writeBaseFrame(ctx, out, ab.squareness, sq);
  writeCrossTable(ctx, out, before, model, sq);
  return chain;
}

}  // namespace pkm::workflow::campaign::detail
