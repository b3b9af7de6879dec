// `pkm calibrate hexapod`: identify a hexapod's 42 kinematic parameters from laser-tracker and
// dial-gauge files and write the calibrated machine, its LinuxCNC setp block and a summary
// (docs/calibration.md).
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "analyze_common.hpp"
#include "calibrate_common.hpp"
#include "cli_common.hpp"
#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/calibration/uncertainty.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/io/calibration_files.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "pkm/io/linuxcnc_hal.hpp"
#include "pkm/io/result_store.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/simulation/hexapod_workspace.hpp"

namespace pkm::cli {
namespace {

namespace cal = pkm::calibration;
using nlohmann::ordered_json;

struct CalibrateArgs {
  MachineOption machine;
  std::vector<std::string> data, holdout;
  std::string out;
  std::string frame = "auto";
  std::vector<double> target_offset;
  std::vector<std::string> fix;
  std::string loss = "none";
  double loss_scale = 0.0;
  bool force = false;
  bool json = false;
  int monte_carlo = 0;
  double sigma_position = 0.0;
  double sigma_orientation_urad = 0.0;
  double sigma_gauge = 0.0;
  int threads = 0;
  bool backlash = false;
  std::string db;                  ///< result store to record the calibration in (empty: none)
  double prior_sigma = 0.0;        ///< Tikhonov prior σ_θ, machine unit (0: none)
  double measurement_sigma = 0.0;  ///< residual σ for the prior and the covariance (0: estimated)
};

/// Held-out TCP position errors: |FK(q) target in the measurement frame − measured|.
struct HoldoutErrors {
  int poses = 0, failures = 0;
  double rms = 0.0, max = 0.0, mean = 0.0;
};

HoldoutErrors holdoutErrors(const kinematics::HexapodModel& model,
                            const std::optional<geometry::RigidTransform>& frame,
                            const cal::HexapodCalibrationData& held,
                            const std::optional<kinematics::StrutVector>& backlash = std::nullopt) {
  HoldoutErrors e;
  kinematics::HexapodData work(model);
  double sum2 = 0.0, sum = 0.0;
  const auto add = [&](const kinematics::StrutVector& readings,
                       const Eigen::Vector3d& measured,
                       const kinematics::StrutVector& approach) {
    kinematics::StrutVector q = readings;
    if (backlash) q -= 0.5 * approach.cwiseProduct(*backlash);  // the estimated hysteresis
    if (!kinematics::forwardKinematics(model, work, q, model.home).ok()) {
      ++e.failures;
      return;
    }
    Eigen::Vector3d p = work.world_p_tcp;
    if (frame) p = frame->rotation.transpose() * (p - frame->translation);
    const double d = (p - measured).norm();
    sum2 += d * d;
    sum += d;
    e.max = std::max(e.max, d);
    ++e.poses;
  };
  for (const auto& o : held.poses) add(o.readings, o.pose.position, o.approach);
  for (const auto& o : held.points) add(o.readings, o.point, o.approach);
  if (e.poses > 0) {
    e.rms = std::sqrt(sum2 / e.poses);
    e.mean = sum / e.poses;
  }
  return e;
}

ordered_json toJson(const HoldoutErrors& e) {
  return {{"poses", e.poses},
          {"fk_failures", e.failures},
          {"mean", e.mean},
          {"rms", e.rms},
          {"max", e.max}};
}

ordered_json toJson(const cal::ResidualStatistics& s) {
  return {
      {"equations", s.equations}, {"rms", s.rms}, {"max", s.max}, {"fk_failures", s.fk_failures}};
}

ordered_json toJson(const cal::TcpErrorStatistics& s) {
  return {{"samples", s.samples}, {"mean", s.mean}, {"p95", s.p95}, {"max", s.max}};
}

/// 200 workspace poses about home (every limit respected) for the TCP error map.
std::vector<kinematics::PoseRpy> workspacePoses(const kinematics::HexapodModel& model) {
  simulation::PoseBox box;
  const double reach = 0.4 * model.characteristicLength();
  for (int i = 0; i < 3; ++i) {
    box.lo(i) = model.home.position(i) - reach;
    box.hi(i) = model.home.position(i) + reach;
    box.lo(3 + i) = model.home.rpy(i) - degToRad(10.0);
    box.hi(3 + i) = model.home.rpy(i) + degToRad(10.0);
  }
  simulation::RandomStream rng(1, "calibration-workspace");
  std::vector<kinematics::PoseRpy> out;
  for (const Eigen::VectorXd& c : simulation::sampleHexapodWorkspace(model, box, 200, rng)) {
    kinematics::PoseRpy p;
    p.position = c.head<3>();
    p.rpy = c.tail<3>();
    out.push_back(p);
  }
  return out;
}

/// `model` (with the target as TCP) under the estimated parameters.
kinematics::HexapodModel fittedModel(const kinematics::HexapodModel& model,
                                     const cal::HexapodParameterVector& parameters) {
  return cal::withHexapodParameters(model, parameters);
}

void runCalibrate(const CalibrateArgs& args) {
  io::HexapodMachine machine = args.machine.load();
  const CalibrationOutputs paths = calibrationOutputs(args.out);
  if (!args.force)
    for (const std::string& p : {paths.machine, paths.hal, paths.summary})
      if (std::filesystem::exists(p))
        throw IoError(fmt::format("{} exists; pass --force to overwrite it", p));
  io::CalibrationInput input, held;
  for (const std::string& f : args.data) io::addCalibrationFile(f, input);
  for (const std::string& f : args.holdout) io::addCalibrationFile(f, held);
  printNotices(input.notes);

  // The target (SMR or 6-DOF probe) is the TCP of the fitted model: tool offset += target offset.
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  if (!args.target_offset.empty()) {
    if (args.target_offset.size() != 3) throw InvalidArgument("--target-offset needs x,y,z");
    target = Eigen::Vector3d(args.target_offset[0], args.target_offset[1], args.target_offset[2]);
  } else if (input.target_offset) {
    target = *input.target_offset;
  }
  kinematics::HexapodModel model = machine.model;
  model.tool_offset += target;

  bool use_frame = args.frame == "tracker" || (args.frame == "auto" && input.tracker_frame);
  if (use_frame && input.data.poses.empty() && input.data.points.empty())
    throw InvalidArgument("--frame tracker needs tracker pose or point data");
  if (use_frame) input.data.measurement_frame = cal::initialMeasurementFrame(model, input.data);
  cal::HexapodCalibrationOptions options;
  for (const std::string& name : args.fix)
    options.free[static_cast<std::size_t>(cal::hexapodParameterIndex(name))] = false;
  if (args.loss == "huber") options.loss = cal::RobustLoss::kHuber;
  if (args.loss == "cauchy") options.loss = cal::RobustLoss::kCauchy;
  options.loss_scale = args.loss_scale;
  options.estimate_backlash = args.backlash;
  options.parameter_prior_sigma = args.prior_sigma;
  options.measurement_sigma = args.measurement_sigma;

  const cal::HexapodCalibrationSummary s = cal::calibrateHexapod(model, input.data, options);
  // Plausibility: a model that cannot explain the data is not written.
  const double scale = model.characteristicLength();
  if (!(s.after.rms < 1e-3 * scale)) {
    throw InvalidArgument(fmt::format(
        "calibration does not explain the data: residual RMS {:.4g} (max {:.4g}) after {} "
        "iterations ({}); check the units of the data against the machine's ({}), the --frame "
        "option, and outliers (--loss cauchy --loss-scale ...); nothing was written",
        s.after.rms,
        s.after.max,
        s.iterations,
        s.termination,
        toString(model.unit)));
  }

  io::HexapodMachine result = machine;
  result.model = cal::withHexapodParameters(machine.model, s.parameters);
  result.model.name = machine.model.name + "-calibrated";
  result.notices.clear();

  ordered_json j;
  j["machine"] = machine.model.name;
  j["units"] = toString(model.unit);
  j["data"] = input.notes;
  j["observations"] = {{"poses", input.data.poses.size()},
                       {"points", input.data.points.size()},
                       {"constrained_sets", input.data.constrained.size()},
                       {"distances", input.data.distances.size()},
                       {"equations", input.data.equations()}};
  j["target_offset"] = {target.x(), target.y(), target.z()};
  j["solver"] = {{"converged", s.converged},
                 {"termination", s.termination},
                 {"iterations", s.iterations},
                 {"initial_cost", s.initial_cost},
                 {"final_cost", s.final_cost},
                 {"seconds", s.seconds}};
  j["residuals"] = {{"before", toJson(s.before)}, {"after", toJson(s.after)}};
  if (!held.data.poses.empty() || !held.data.points.empty()) {
    // Before: the nominal model with the frame fitted through it; after: the calibrated model and
    // the estimated frame.
    // The held-out files' own target (it may differ from the fitted data's).
    const Eigen::Vector3d held_target = held.target_offset.value_or(target);
    kinematics::HexapodModel before_model = machine.model, after_model = result.model;
    before_model.tool_offset += held_target;
    after_model.tool_offset += held_target;
    std::optional<geometry::RigidTransform> f0, f1 = s.measurement_frame;
    if (use_frame) f0 = cal::initialMeasurementFrame(model, input.data);
    j["holdout"] = {{"target_offset", {held_target.x(), held_target.y(), held_target.z()}},
                    {"before", toJson(holdoutErrors(before_model, f0, held.data))},
                    {"after", toJson(holdoutErrors(after_model, f1, held.data, s.backlash))}};
  }
  ordered_json id;
  id["parameters"] = s.identifiability.parameters;
  id["rank"] = s.identifiability.rank;
  id["condition_number"] = s.identifiability.condition_number;
  id["unidentifiable"] = ordered_json::array();
  for (const auto& c : s.identifiability.combinations) {
    ordered_json terms = ordered_json::object();
    for (const auto& [name, coef] : c.terms) terms[name] = coef;
    id["unidentifiable"].push_back(terms);
  }
  j["identifiability"] = id;
  if (s.measurement_frame) {
    j["measurement_frame"] = frameJson(*s.measurement_frame);
    j["measurement_frame"]["sigma"] = std::vector<double>(s.frame_standard_deviation.data(),
                                                          s.frame_standard_deviation.data() + 6);
  }
  j["sigma"] = s.sigma;
  if (s.backlash)
    j["backlash"] = {{"values", std::vector<double>(s.backlash->data(), s.backlash->data() + 6)},
                     {"sigma",
                      std::vector<double>(s.backlash_standard_deviation.data(),
                                          s.backlash_standard_deviation.data() + 6)},
                     {"approach", "from the row order of each file (first row unknown)"}};
  // Outlier diagnostics: the observations with the largest residuals after the fit, by source.
  {
    const std::vector<double> norms = cal::observationResidualNorms(
        fittedModel(model, s.parameters), input.data, s.measurement_frame);
    std::vector<std::string> sources = input.pose_origin;
    sources.insert(sources.end(), input.point_origin.begin(), input.point_origin.end());
    for (std::size_t c = 0; c < input.data.constrained.size(); ++c)
      for (std::size_t k = 0; k < input.data.constrained[c].stations.size(); ++k)
        sources.push_back(fmt::format("constrained set {} station {}", c + 1, k + 1));
    sources.insert(sources.end(), input.distance_origin.begin(), input.distance_origin.end());
    std::vector<std::size_t> order(norms.size());
    for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return norms[a] > norms[b];
    });
    ordered_json worst = ordered_json::array();
    for (std::size_t k = 0; k < std::min<std::size_t>(5, order.size()); ++k)
      worst.push_back({{"source", order[k] < sources.size() ? sources[order[k]] : "?"},
                       {"residual", norms[order[k]]}});
    j["worst_observations"] = worst;
  }
  // The TCP error over the workspace: the nominal controller on the calibrated machine (what
  // calibration removes), and with --monte-carlo the spread the calibration itself leaves.
  const std::vector<kinematics::PoseRpy> workspace = workspacePoses(machine.model);
  ordered_json map;
  map["poses"] = workspace.size();
  map["before"] = toJson(cal::tcpErrorOverWorkspace(machine.model, result.model, workspace));
  if (args.monte_carlo > 0) {
    cal::MonteCarloOptions mc;
    mc.trials = args.monte_carlo;
    mc.threads = args.threads;
    mc.position_sigma = args.sigma_position > 0.0 ? args.sigma_position : s.sigma;
    mc.orientation_sigma = args.sigma_orientation_urad * 1e-6;
    mc.gauge_sigma = args.sigma_gauge > 0.0 ? args.sigma_gauge : s.sigma;
    const bool tty = ::isatty(STDERR_FILENO) != 0;
    mc.progress = [tty](int done, int total) {
      if (tty) fmt::print(stderr, "\rpkm: Monte Carlo {}/{}", done, total);
    };
    kinematics::HexapodModel estimate = model;  // the fitted model with the target as TCP
    estimate = cal::withHexapodParameters(estimate, s.parameters);
    std::vector<kinematics::PoseRpy> ws_target = workspace;
    const cal::MonteCarloSummary u = cal::monteCarloHexapod(
        model, input.data, estimate, s.measurement_frame, ws_target, options, mc);
    if (tty) fmt::print(stderr, "\n");
    map["after"] = toJson(u.tcp);
    ordered_json mcj;
    mcj["trials"] = u.trials;
    mcj["failures"] = u.failures;
    mcj["not_converged"] = u.not_converged;
    mcj["seconds"] = u.seconds;
    mcj["sigma_position"] = mc.position_sigma;
    mcj["sigma_orientation"] = mc.orientation_sigma;
    mcj["sigma_gauge"] = mc.gauge_sigma;
    mcj["parameter_sigma"] = std::vector<double>(
        u.standard_deviation.data(), u.standard_deviation.data() + cal::kHexapodParameters);
    j["monte_carlo"] = mcj;
  }
  j["tcp_error_map"] = map;
  ordered_json params = ordered_json::array();
  for (int k = 0; k < cal::kHexapodParameters; ++k)
    params.push_back({{"name", cal::hexapodParameterName(k)},
                      {"free", options.free[static_cast<std::size_t>(k)]},
                      {"initial", s.initial(k)},
                      {"estimate", s.parameters(k)},
                      {"change", s.parameters(k) - s.initial(k)},
                      {"sigma", s.standard_deviation(k)}});
  j["parameters"] = params;
  j["outputs"] = {{"machine", paths.machine}, {"hal", paths.hal}, {"summary", paths.summary}};

  writeOutputFile(paths.machine, io::writeHexapodJson(result));
  writeOutputFile(paths.hal, io::writeLinuxcncSetp(result));
  writeOutputFile(paths.summary, j.dump(2) + "\n");
  if (!args.db.empty())
    recordCalibration(args.db,
                      machine.model.name,
                      "hexapod",
                      "calibrate hexapod",
                      args.data,
                      j,
                      std::string(toString(model.unit)),
                      {{"linuxcnc-hal", paths.hal}, {"machine-json", paths.machine}});
  if (args.json) {
    printJson(j);
    return;
  }
  Output out;
  std::string& t = out.text();
  t += fmt::format("calibrated {} from {} equations ({} poses, {} points, {} gauge sets)\n",
                   machine.model.name,
                   input.data.equations(),
                   input.data.poses.size(),
                   input.data.points.size(),
                   input.data.constrained.size());
  t += fmt::format("solver: {} iterations, {:.3f} s, {}\n",
                   s.iterations,
                   s.seconds,
                   s.converged ? "converged" : s.termination);
  if (!s.converged && !input.data.constrained.empty() && args.prior_sigma == 0.0)
    t += "  dial-gauge data see some combinations only weakly: --prior-sigma (with "
         "--measurement-sigma) keeps them near the machine file (docs/calibration.md)\n";
  t += fmt::format("identifiable: {} of {} unknowns (condition number {:.4g})\n",
                   s.identifiability.rank,
                   s.identifiability.parameters,
                   s.identifiability.condition_number);
  for (const auto& c : s.identifiability.combinations) {
    std::string terms;
    for (const auto& [name, coef] : c.terms) terms += fmt::format(" {:+.3f}·{}", coef, name);
    t += fmt::format("  not identifiable:{}\n", terms);
  }
  t += fmt::format("fitted residuals ({}): RMS {:.6g} -> {:.6g}, max {:.6g} -> {:.6g}\n",
                   toString(model.unit),
                   s.before.rms,
                   s.after.rms,
                   s.before.max,
                   s.after.max);
  if (!j["worst_observations"].empty())
    t += fmt::format("largest residual after the fit: {} ({:.4g})\n",
                     j["worst_observations"][0]["source"].get<std::string>(),
                     j["worst_observations"][0]["residual"].get<double>());
  if (s.backlash)
    t += fmt::format(
        "backlash per strut ({}): {:.4g}\n",
        toString(model.unit),
        fmt::join(std::vector<double>(s.backlash->data(), s.backlash->data() + 6), ", "));
  if (j.contains("holdout"))
    t += fmt::format("held-out TCP error: RMS {:.6g} -> {:.6g}, max {:.6g} -> {:.6g}\n",
                     j["holdout"]["before"]["rms"].get<double>(),
                     j["holdout"]["after"]["rms"].get<double>(),
                     j["holdout"]["before"]["max"].get<double>(),
                     j["holdout"]["after"]["max"].get<double>());
  t += fmt::format(
      "workspace TCP error of the nominal controller (what calibration removes): "
      "mean {:.6g}, 95 % {:.6g}, max {:.6g}\n",
      map["before"]["mean"].get<double>(),
      map["before"]["p95"].get<double>(),
      map["before"]["max"].get<double>());
  if (map.contains("after"))
    t += fmt::format(
        "workspace TCP uncertainty after calibration (Monte Carlo, {} trials): mean "
        "{:.6g}, 95 % {:.6g}, max {:.6g}\n",
        args.monte_carlo,
        map["after"]["mean"].get<double>(),
        map["after"]["p95"].get<double>(),
        map["after"]["max"].get<double>());
  t += fmt::format("wrote {}, {}, {}\n", paths.machine, paths.hal, paths.summary);
}

}  // namespace

ordered_json frameJson(const geometry::RigidTransform& f) {
  const Eigen::Vector3d rpy = geometry::rpyFromRotation(f.rotation);
  return {{"position", {f.translation.x(), f.translation.y(), f.translation.z()}},
          {"rpy_deg", {radToDeg(rpy.x()), radToDeg(rpy.y()), radToDeg(rpy.z())}}};
}

CalibrationOutputs calibrationOutputs(const std::string& out) {
  std::string stem = out;
  if (stem.size() > 5 && stem.ends_with(".json")) stem.resize(stem.size() - 5);
  return {out, stem + ".hal", stem + ".summary.json"};
}

namespace {

/// Adds the numeric leaves under `j` (path `prefix`) as results; a path component "before",
/// "after" becomes the stage.
void addLeaves(const ordered_json& j,
               const std::string& prefix,
               const std::string& stage,
               const std::string& unit,
               std::vector<io::ResultRecord>& out) {
  if (j.is_number()) {
    const double v = j.get<double>();
    if (std::isfinite(v)) out.push_back({prefix, stage.empty() ? "estimate" : stage, v, unit});
    return;
  }
  if (j.is_array()) {
    for (std::size_t k = 0; k < j.size(); ++k)
      addLeaves(j[k], fmt::format("{}.{}", prefix, k), stage, unit, out);
    return;
  }
  if (!j.is_object()) return;
  for (const auto& [key, value] : j.items()) {
    if (key == "before" || key == "after") {
      addLeaves(value, prefix, key, unit, out);
      continue;
    }
    if (key == "equations" || key == "poses" || key == "points" || key == "fk_failures" ||
        key == "failures")
      continue;  // counts, not results
    addLeaves(value, prefix.empty() ? key : fmt::format("{}.{}", prefix, key), stage, unit, out);
  }
}

}  // namespace

void recordCalibration(const std::string& db,
                       const std::string& machine,
                       const std::string& machine_type,
                       const std::string& campaign,
                       const std::vector<std::string>& files,
                       const ordered_json& summary,
                       const std::string& length_unit,
                       const std::vector<std::pair<std::string, std::string>>& compensations) {
  io::CampaignRecord c;
  c.machine = machine;
  c.machine_type = machine_type;
  c.name = campaign;
  c.source = fmt::format("{}", fmt::join(files, " "));
  for (const std::string& f : files) c.measurements.push_back({f, "calibration-data", f, 0});
  for (const char* key : {"residuals", "holdout", "tcp_error_map"})
    if (summary.contains(key)) addLeaves(summary[key], key, "", length_unit, c.results);
  if (summary.contains("backlash"))
    addLeaves(summary["backlash"]["values"], "backlash", "estimate", length_unit, c.results);
  if (summary.contains("hybrid")) {
    const ordered_json& h = summary["hybrid"];
    addLeaves(h["squareness"], "squareness", "estimate", "rad", c.results);
    addLeaves(h["residuals"], "hybrid.residuals", "", length_unit, c.results);
    if (h.contains("holdout"))
      addLeaves(h["holdout"], "hybrid.holdout", "", length_unit, c.results);
  }
  for (const auto& [target, path] : compensations) {
    std::ifstream in(path, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    c.compensations.push_back({target, path, text});
  }
  io::ResultStore store(db);
  (void)store.store(c);
}

void writeOutputFile(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  if (!f) throw IoError(locate(path, 0, "cannot write the file"));
  f << text;
  if (!f) throw IoError(locate(path, 0, "write failed"));
}

void addCalibrateCommand(CLI::App& app) {
  CLI::App* calibrate =
      app.add_subcommand("calibrate", "identify kinematic parameters from measurements");
  calibrate->require_subcommand(1);
  auto args = std::make_shared<CalibrateArgs>();
  CLI::App* hex = calibrate->add_subcommand(
      "hexapod", "calibrate a hexapod from laser-tracker pose/point files and dial-gauge files");
  args->machine.add(*hex);
  hex->add_option(
         "--data", args->data, "calibration files (tracker pose/point, constrained motion)")
      ->required()
      ->check(CLI::ExistingFile);
  hex->add_option("--holdout", args->holdout, "tracker files kept out of the fit, for validation")
      ->check(CLI::ExistingFile);
  hex->add_option(
         "--out", args->out, "calibrated machine file CAL.json (also CAL.hal, CAL.summary.json)")
      ->required();
  hex->add_option("--frame",
                  args->frame,
                  "where tracker readings are: auto (from the files' metadata), world, tracker")
      ->check(CLI::IsMember({"auto", "world", "tracker"}));
  hex->add_option("--target-offset",
                  args->target_offset,
                  "the tracker target in the tool frame x,y,z (default: the files' smr offset)")
      ->delimiter(',')
      ->expected(3);
  hex->add_option("--fix", args->fix, "parameters held at their initial value (e.g. offset0)")
      ->delimiter(',');
  hex->add_option("--loss", args->loss, "robust loss: none, huber, cauchy")
      ->check(CLI::IsMember({"none", "huber", "cauchy"}));
  hex->add_option("--loss-scale", args->loss_scale, "robust loss scale, machine unit");
  hex->add_flag("--force", args->force, "overwrite existing output files");
  hex->add_flag("--json", args->json, "print the summary as JSON");
  hex->add_option("--monte-carlo",
                  args->monte_carlo,
                  "also run N Monte Carlo trials of the calibration under simulated noise")
      ->check(CLI::Range(2, 100000));
  hex->add_option("--sigma-position",
                  args->sigma_position,
                  "Monte Carlo: position noise, machine unit (default: the fitted residual sigma)");
  hex->add_option("--sigma-orientation",
                  args->sigma_orientation_urad,
                  "Monte Carlo: 6-DOF orientation noise, urad (default 0)");
  hex->add_option(
      "--sigma-gauge",
      args->sigma_gauge,
      "Monte Carlo: dial-gauge noise, machine unit (default: the fitted residual sigma)");
  hex->add_option("--threads", args->threads, "Monte Carlo worker threads (default: all cores)");
  hex->add_option("--db", args->db, "also record the calibration in this result store (pkm.db)");
  hex->add_option("--prior-sigma",
                  args->prior_sigma,
                  "regularise toward the machine file: how far the true geometry may plausibly be, "
                  "machine unit (needs --measurement-sigma; for dial-gauge data)");
  hex->add_option("--measurement-sigma",
                  args->measurement_sigma,
                  "residual sigma, machine unit, for --prior-sigma and the covariance (default: "
                  "estimated from the residuals)");
  hex->add_flag("--backlash",
                args->backlash,
                "also estimate a per-strut backlash; approach directions follow from the row order "
                "of each file (one continuous sequence of moves per file)");
  hex->callback([args] { runCalibrate(*args); });
  addCalibrateExechon(*calibrate);
}

}  // namespace pkm::cli
