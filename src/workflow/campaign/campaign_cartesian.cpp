// Campaign step "cartesian-diagonals" (Hwang et al., "Analysis of multi-axis volumetric errors"):
// body diagonals (ISO 230-6) of a Cartesian machine give its three squareness errors; they are
// compensated by a linear command correction and the X and Y positioning by LinuxCNC axis tables;
// the diagonals are measured again (docs/campaign.md).
#include <fmt/format.h>

#include <Eigen/LU>
#include <cmath>
#include <tuple>
#include <utility>

#include "campaign_compensation.hpp"
#include "campaign_steps.hpp"
#include "pkm/compensation/axis_table.hpp"
#include "pkm/core/error.hpp"
#include "pkm/metrology/body_diagonals.hpp"
#include "pkm/metrology/squareness_uncertainty.hpp"
#include "pkm/simulation/cartesian_machine.hpp"

namespace pkm::workflow::campaign {

namespace sim = pkm::simulation;
namespace met = pkm::metrology;
namespace comp = pkm::compensation;

namespace {

const std::array<std::string, 4> kDiagonals = {"diag-ppp", "diag-npp", "diag-pnp", "diag-nnp"};

struct Analysis {
  met::BodyDiagonalResult body;
  double max_length_error = 0.0;             ///< max |ΔD| of the four diagonals, mm
  double max_length_error_U = std::nan("");  ///< its U (k = 2), mm
  met::Iso230_2Result face_pp, face_np, linear_x, linear_y;
  /// The budgets' sources at the conditions the data recorded (sourcesAt).
  met::UncertaintySources sources;
};

/// The analysis of `d`, with the uncertainty budgets of `ctx.sources` at the conditions `d`
/// recorded.
Analysis analyse(const LineData& d, const Eigen::Vector3d& size, const StepContext& ctx) {
  const std::string& src = ctx.source;
  Analysis a;
  a.sources = sourcesAt(ctx.sources, d);
  std::vector<met::BodyDiagonalSample> samples;
  for (std::size_t k = 0; k < 4; ++k)
    for (const sim::LineRun& run : d.runs(kDiagonals[k], src))
      for (const sim::LineReading& r : run.readings)
        samples.push_back(
            {met::kBodyDiagonals[k], r.target, r.reading - r.target, run.run, r.direction});
  met::BodyDiagonalOptions options;
  options.iso230_2 = false;
  a.body = met::evaluateBodyDiagonals(samples, size, options);
  for (std::size_t k = 0; k < 4; ++k) {
    const double e = std::abs(a.body.diagonals[k].length_error);
    if (k > 0 && e <= a.max_length_error) continue;
    a.max_length_error = e;
    a.max_length_error_U =
        met::bodyDiagonalLengthErrorUncertainty(samples, a.body, met::kBodyDiagonals[k], a.sources)
            .expandedUncertainty();
  }
  a.face_pp = iso230_2(d.runs("face-xy-pp", src));
  a.face_np = iso230_2(d.runs("face-xy-np", src));
  a.linear_x = iso230_2(d.runs("linear-x", src));
  a.linear_y = iso230_2(d.runs("linear-y", src));
  return a;
}

/// The squareness correction q' = D⁻¹·q, D the axis directions of the machine with the estimated
/// squareness (CartesianMachine::axisDirection), so that the estimated machine's axes reach q.
class SquarenessController final : public sim::CommandCompensation {
 public:
  explicit SquarenessController(const Eigen::Matrix3d& inverse) : inverse_(inverse) {}
  [[nodiscard]] Eigen::VectorXd apply(const Eigen::VectorXd& command) override {
    return inverse_ * command;
  }

 private:
  Eigen::Matrix3d inverse_;
};

/// The Cartesian axes in command order.
const std::vector<std::string> kAxes = {"x", "y", "z"};

/// The box of the body diagonals: |direction · travel| of "diag-ppp".
Eigen::Vector3d diagonalBox(const LineData& d, const std::string& src) {
  const sim::LineSetup& m = d.setup("diag-ppp", src);
  return (m.line.direction * (m.cycle.last - m.cycle.first)).head<3>().cwiseAbs();
}

/// Writes the squareness correction and the X/Y axis tables of `ab` and returns them as the
/// controller's command compensation.
std::shared_ptr<sim::CompensationChain> compensate(const StepContext& ctx,
                                                   StepOutcome& out,
                                                   const LineData& before,
                                                   const sim::CartesianLayout& layout,
                                                   const Analysis& ab) {
  sim::CartesianErrors estimated;
  estimated.squareness = {ab.body.solution.squareness_xy,
                          ab.body.solution.squareness_xz,
                          ab.body.solution.squareness_yz};
  const sim::CartesianMachine model(layout, estimated);
  Eigen::Matrix3d D;
  for (int k = 0; k < 3; ++k) D.col(k) = model.axisDirection(k);
  auto chain = std::make_shared<sim::CompensationChain>();
  chain->add(std::make_shared<SquarenessController>(D.inverse()));
  auto axes = std::make_shared<AxisTableController>(3);
  writeAxisTables(ctx, out, before, {{"linear-x", 0}, {"linear-y", 1}}, kAxes, *axes);
  chain->add(axes);
  const Eigen::Matrix3d Di = D.inverse();
  const std::string sq_text = fmt::format(
      "# squareness correction (body diagonals): q_sent = M * q\n# xy {:.6e} xz {:.6e} yz {:.6e} "
      "rad\n"
      "M = {:.9e} {:.9e} {:.9e}\n    {:.9e} {:.9e} {:.9e}\n    {:.9e} {:.9e} {:.9e}\n",
      estimated.squareness.xy,
      estimated.squareness.xz,
      estimated.squareness.yz,
      Di(0, 0),
      Di(0, 1),
      Di(0, 2),
      Di(1, 0),
      Di(1, 1),
      Di(1, 2),
      Di(2, 0),
      Di(2, 1),
      Di(2, 2));
  ctx.writeCompensation(out, "squareness-matrix", "compensation/squareness.txt", sq_text);

  return chain;
}

/// The step on measured laser files ("data": {"folder": DIR}): squareness and compensation
/// files, no re-measurement (docs/campaign.md, "Measured data").
StepOutcome fromFiles(const StepContext& ctx) {
  const std::string folder = dataFolder(ctx);
  sim::CartesianLayout layout;
  layout.order = ctx.spec.value("order", std::string("XYZ"));
  try {
    layout.validate();
  } catch (const InvalidArgument& e) {
    throw IoError(fmt::format("{}: \"order\": {}", ctx.source, e.what()));
  }
  StepOutcome out;
  out.id = ctx.spec.value("id", std::string("seed001"));
  out.title = "Cartesian machine: squareness from body diagonals in measured files";
  out.record.machine = ctx.spec.value("machine", std::string("cartesian machine"));
  out.record.machine_type = "cartesian";
  const LineFiles files = readLineFolder(ctx, folder);
  out.record.source = fmt::format("{} files", files.paths.size());
  for (const std::string& p : files.paths)
    out.record.measurements.push_back({std::filesystem::path(p).stem().string(), "laser", p, 0});
  ctx.progress(fmt::format("analyse: {} laser files", files.paths.size()));
  const Analysis ab = analyse(files.data, diagonalBox(files.data, ctx.source), ctx);
  (void)compensate(ctx, out, files.data, layout, ab);
  const std::pair<const char*, double> figures[] = {
      {"body diagonals, max |length error|", ab.max_length_error},
      {"X positioning (ISO 230-2 E)", ab.linear_x.E},
      {"Y positioning (ISO 230-2 E)", ab.linear_y.E}};
  for (const auto& [quantity, value] : figures)
    out.rows.push_back({quantity, "mm", value, std::nan(""), std::nullopt, "", "as measured"});
  const double U[] = {ab.max_length_error_U,
                      iso230_2U(ab.linear_x, "E", ab.sources),
                      iso230_2U(ab.linear_y, "E", ab.sources)};
  for (std::size_t k = 0; k < 3; ++k) out.rows[out.rows.size() - 3 + k].before_U = U[k];
  const met::BodyDiagonalSolution& sb = ab.body.solution;
  out.record.results.push_back({"squareness.xy", "estimate", sb.squareness_xy, "rad"});
  out.record.results.push_back({"squareness.xz", "estimate", sb.squareness_xz, "rad"});
  out.record.results.push_back({"squareness.yz", "estimate", sb.squareness_yz, "rad"});
  Json sec = section(
      out.id,
      out.title,
      {fmt::format(
          "Measured files: {} in {}; compensation in compensation/.", files.paths.size(), folder)});
  Json st = table("Squareness from the body diagonals (µrad)", {"angle", "estimate"});
  st["rows"].push_back({"xy", cell(sb.squareness_xy * 1e6)});
  st["rows"].push_back({"xz", cell(sb.squareness_xz * 1e6)});
  st["rows"].push_back({"yz", cell(sb.squareness_yz * 1e6)});
  sec["tables"].push_back(st);
  out.section = std::move(sec);
  return out;
}

/// The box of the body diagonals of a scenario: |direction · travel| of "diag-ppp". Throws
/// pkm::IoError naming `src` when there is no such measurement.
Eigen::Vector3d scenarioBox(const io::Scenario& scenario, const std::string& src) {
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  for (const sim::LineSetup& m : scenario.campaign.measurements)
    if (m.name == "diag-ppp")
      size = (m.line.direction * (m.cycle.last - m.cycle.first)).head<3>().cwiseAbs();
  if (!(size.minCoeff() > 0))
    throw IoError(fmt::format("{}: the scenario needs the body diagonal 'diag-ppp'", src));
  return size;
}

/// The summary rows before and after compensation, and the estimated squareness for the store.
void addRows(StepOutcome& out,
             const LineData& before,
             const Analysis& ab,
             const Analysis& aa,
             const StepContext& ctx) {
  const std::string& src = ctx.source;
  const metrology::UncertaintySources& u = ab.sources;
  const metrology::UncertaintySources& ua = aa.sources;
  const sim::LineSetup& li = before.setup("diag-ppp", src);
  const std::string noise =
      fmt::format("laser {:g} µm + {:g} ppm", li.noise.sigma * 1e3, li.noise.sigma_ppm);
  const std::tuple<const char*, double, double> figures[] = {
      {"body diagonals, max |length error|", ab.max_length_error, aa.max_length_error},
      {"face diagonal XY (PP) error (ISO 230-2 E)", ab.face_pp.E, aa.face_pp.E},
      {"face diagonal XY (NP) error (ISO 230-2 E)", ab.face_np.E, aa.face_np.E},
      {"X positioning (ISO 230-2 E)", ab.linear_x.E, aa.linear_x.E},
      {"Y positioning (ISO 230-2 E)", ab.linear_y.E, aa.linear_y.E}};
  for (const auto& [quantity, b, a] : figures)
    out.rows.push_back({quantity, "mm", b, a, std::nullopt, "", noise});
  const std::pair<double, double> U[] = {
      {ab.max_length_error_U, aa.max_length_error_U},
      {iso230_2U(ab.face_pp, "E", u), iso230_2U(aa.face_pp, "E", ua)},
      {iso230_2U(ab.face_np, "E", u), iso230_2U(aa.face_np, "E", ua)},
      {iso230_2U(ab.linear_x, "E", u), iso230_2U(aa.linear_x, "E", ua)},
      {iso230_2U(ab.linear_y, "E", u), iso230_2U(aa.linear_y, "E", ua)}};
  for (std::size_t k = 0; k < 5; ++k) {
    SummaryRow& row = out.rows[out.rows.size() - 5 + k];
    std::tie(row.before_U, row.after_U) = U[k];
  }
  const std::size_t first = out.rows.size() - 5;
  setIso230_2AfterU(out.rows[first + 1], aa.face_pp, "E", ua);
  setIso230_2AfterU(out.rows[first + 2], aa.face_np, "E", ua);
  setIso230_2AfterU(out.rows[first + 3], aa.linear_x, "E", ua);
  setIso230_2AfterU(out.rows[first + 4], aa.linear_y, "E", ua);
  const met::BodyDiagonalSolution& sb = ab.body.solution;
  out.record.results.push_back({"squareness.xy", "estimate", sb.squareness_xy, "rad"});
  out.record.results.push_back({"squareness.xz", "estimate", sb.squareness_xz, "rad"});
  out.record.results.push_back({"squareness.yz", "estimate", sb.squareness_yz, "rad"});
}

/// The squareness before and after compensation, and the injected one.
Json squarenessTable(const Analysis& ab, const Analysis& aa, const sim::CartesianSquareness& t) {
  const met::BodyDiagonalSolution& sb = ab.body.solution;
  const met::BodyDiagonalSolution& sa = aa.body.solution;
  Json st = table("Squareness (µrad): body diagonals before and after compensation, injected",
                  {"angle", "before", "after", "truth"});
  st["rows"].push_back(
      {"xy", cell(sb.squareness_xy * 1e6), cell(sa.squareness_xy * 1e6), cell(t.xy * 1e6)});
  st["rows"].push_back(
      {"xz", cell(sb.squareness_xz * 1e6), cell(sa.squareness_xz * 1e6), cell(t.xz * 1e6)});
  st["rows"].push_back(
      {"yz", cell(sb.squareness_yz * 1e6), cell(sa.squareness_yz * 1e6), cell(t.yz * 1e6)});
  return st;
}

/// The length errors of the four body diagonals, before and after.
Json bodyPlot(const std::string& id, const Analysis& ab, const Analysis& aa) {
  Json p = plot(
      id + "-body", "Body diagonal length errors (seed 001 Fig. 5)", "bar", "diagonal", "ΔD (µm)");
  p["categories"] = Json::array({"PPP", "NPP", "PNP", "NNP"});
  for (const auto& [a, label] : {std::pair{&ab, "before"}, std::pair{&aa, "after"}}) {
    Json ys = Json::array();
    for (const met::DiagonalEvaluation& e : a->body.diagonals)
      ys.push_back(cell(e.length_error * 1e3));
    p["series"].push_back(Json{{"label", label}, {"y", ys}});
  }
  return p;
}

/// The deviation along the XY (PP) face diagonal, before and after.
Json facePlot(const std::string& id,
              const LineData& before,
              const LineData& after,
              const std::string& src) {
  Json f = plot(
      id + "-face", "Face diagonal XY (PP): deviation", "line", "position (mm)", "deviation (µm)");
  for (const auto& [d, label] : {std::pair{&before, "before"}, std::pair{&after, "after"}}) {
    std::vector<double> s, m;
    meanReadings(d->runs("face-xy-pp", src), s, m);
    for (std::size_t i = 0; i < s.size(); ++i) m[i] = (m[i] - s[i]) * 1e3;
    addSeries(f, label, s, m);
  }
  return f;
}

}  // namespace

StepOutcome runCartesianDiagonalsStep(const StepContext& ctx) {
  if (ctx.spec.contains("data")) return fromFiles(ctx);
  std::uint64_t seed = 0;
  io::Scenario scenario = stepScenario(ctx, seed);
  const auto vm = scenarioMachine<sim::CartesianMachine>(ctx, scenario, "Cartesian-machine");
  const std::string& src = ctx.source;
  StepOutcome out;
  out.id = ctx.spec.value("id", std::string("seed001"));
  out.title = "Cartesian machine: squareness from body diagonals (seed 001)";
  out.record.machine = scenario.campaign.name;
  out.record.machine_type = "cartesian";
  out.record.source = scenario.source;
  const Eigen::Vector3d size = scenarioBox(scenario, src);

  ctx.progress("measure: body, face and shifted diagonals, positioning and straightness");
  const LineData before{sim::runCampaign(scenario.campaign, seed),
                        setupRecords(scenario.campaign.environment)};
  writeLineFiles(ctx, out, "measured-before", scenario, seed, before);
  ctx.progress("analyse: squareness from the four body diagonals (ISO 230-6)");
  const Analysis ab = analyse(before, size, ctx);

  const std::shared_ptr<sim::CompensationChain> chain =
      compensate(ctx, out, before, vm->layout(), ab);

  ctx.progress("re-measure: the same lines through the compensating controller");
  io::Scenario again = remeasureScenario(scenario);
  again.campaign.machine = std::make_shared<sim::CompensatedMachine>(vm, chain);
  const LineData after{sim::runCampaign(again.campaign, remeasureSeed(seed)),
                       setupRecords(again.campaign.environment)};
  writeLineFiles(ctx, out, "measured-after", scenario, remeasureSeed(seed), after);
  const Analysis aa = analyse(after, size, ctx);
  addRows(out, before, ab, aa, ctx);

  Json sec =
      section(out.id,
              out.title,
              {fmt::format("Scenario {} (seed {}): {}",
                           scenario.campaign.name,
                           seed,
                           scenario.campaign.description),
               "Analysis: the four body diagonals' length errors give the three squareness "
               "errors and the volumetric scale (ISO 230-6). "
               "Compensation: the command correction q' = D⁻¹·q with D the axis directions of "
               "the estimated squareness (compensation/squareness.txt) and LinuxCNC COMP_FILE "
               "type 1 tables of X and Y (compensation/*.comp)."});
  sec["tables"].push_back(squarenessTable(ab, aa, vm->errors().squareness));
  sec["plots"].push_back(bodyPlot(out.id, ab, aa));
  sec["plots"].push_back(facePlot(out.id, before, after, src));
  out.section = std::move(sec);
  return out;
}

}  // namespace pkm::workflow::campaign
