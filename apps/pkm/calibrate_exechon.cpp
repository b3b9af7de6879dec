// `pkm calibrate exechon`: identify an Exechon's 26 kinematic parameters (Zoppi's tripod
// dimensions with the base U-joint axis offsets, leg offsets, wrist zeros, tool length, base
// placement) from laser-tracker files and write the calibrated machine file and a summary
// (docs/calibration.md, "Exechon").
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "analyze_common.hpp"
#include "calibrate_common.hpp"
#include "cli_common.hpp"
#include "pkm/calibration/exechon_calibration.hpp"
#include "pkm/calibration/exechon_uncertainty.hpp"
#include "pkm/calibration/hybrid_calibration.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/exechon_machine.hpp"
#include "pkm/io/exechon_tracker_files.hpp"
#include "pkm/io/geometric_errors.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/exechon_checks.hpp"
#include "pkm/kinematics/exechon_data.hpp"
#include "pkm/simulation/hybrid_tripod_errors.hpp"
#include "pkm/workflow/calibrate_hexapod.hpp"
#include "pkm/workflow/calibration_record.hpp"

namespace pkm::cli {
namespace {

namespace cal = pkm::calibration;
namespace sim = pkm::simulation;
using nlohmann::ordered_json;

struct ExechonArgs {
  std::string machine = "mxt700s-like";
  std::vector<std::string> data, holdout;
  std::string out;
  std::string frame = "auto";
  std::vector<double> target_offset;
  std::vector<std::string> fix;
  std::string loss = "none";
  double loss_scale = 0.0;
  bool force = false;
  bool json = false;
  std::string errors;                   ///< known geometric errors (PDGE) of a hybrid machine
  std::string db;                       ///< result store to record the calibration in (empty: none)
  int monte_carlo = 0;                  ///< Monte Carlo trials (0: none)
  double sigma_position = 0.0;          ///< Monte Carlo point noise, machine unit (0: fitted σ)
  double sigma_orientation_urad = 0.0;  ///< Monte Carlo direction noise, µrad
  int threads = 0;                      ///< Monte Carlo worker threads (0: all cores)
};

ordered_json toJson(const cal::ResidualStatistics& s) {
  return {
      {"equations", s.equations}, {"rms", s.rms}, {"max", s.max}, {"fk_failures", s.fk_failures}};
}

/// Target errors |predicted − measured (in frame)| over held-out data: RMS of the 3-D error, max.
ordered_json holdout(const kinematics::ExechonModel& model,
                     const std::optional<geometry::RigidTransform>& frame,
                     const cal::ExechonCalibrationData& data,
                     const kinematics::FkOptions& fk) {
  double sum = 0.0, worst = 0.0;
  int n = 0, failures = 0;
  for (const cal::ExechonObservation& o : data.observations) {
    const auto p = cal::exechonTarget(model, o.joints, data.target_offset, model.home, fk);
    if (!p) {
      ++failures;
      continue;
    }
    const Eigen::Vector3d m =
        frame ? Eigen::Vector3d(frame->rotation * o.point + frame->translation) : o.point;
    const double e = (m - *p).norm();
    sum += e * e;
    worst = std::max(worst, e);
    ++n;
  }
  return {{"poses", n},
          {"failures", failures},
          {"rms", n > 0 ? std::sqrt(sum / n) : 0.0},
          {"max", worst}};
}

/// mean, 95 %, max of `values` (empty: nullopt).
std::optional<ordered_json> statisticsJson(std::vector<double> values) {
  if (values.empty()) return std::nullopt;
  std::sort(values.begin(), values.end());
  double mean = 0.0;
  for (const double e : values) mean += e / static_cast<double>(values.size());
  const auto p95 = values[static_cast<std::size_t>(0.95 * static_cast<double>(values.size() - 1))];
  return ordered_json{
      {"points", values.size()}, {"mean", mean}, {"p95", p95}, {"max", values.back()}};
}

/// A reachable point of the PKM working-box grid: the tool point and the nominal solution there.
struct GridPoint {
  Eigen::Vector3d position;
  kinematics::ExechonJoints joints;
  kinematics::ExechonConfiguration seed;
};

/// The PKM working box of a hybrid machine sampled 5 × 5 × 5 with the tool vertical (−z), the
/// points the nominal machine reaches within its limits; empty without a finite working box.
std::vector<GridPoint> workingBoxGrid(const io::ExechonMachine& machine) {
  std::vector<GridPoint> out;
  if (!machine.hybrid) return out;
  const Eigen::Vector3d lo = machine.hybrid->pkm_min, hi = machine.hybrid->pkm_max;
  if (!lo.allFinite() || !hi.allFinite()) return out;
  kinematics::ExechonData nom(machine.model);
  constexpr int kSteps = 5;
  for (int i = 0; i < kSteps; ++i)
    for (int j = 0; j < kSteps; ++j)
      for (int k = 0; k < kSteps; ++k) {
        const Eigen::Vector3d f(i / (kSteps - 1.0), j / (kSteps - 1.0), k / (kSteps - 1.0));
        kinematics::ExechonToolPose target;
        target.position = lo + f.cwiseProduct(hi - lo);
        target.direction = -Eigen::Vector3d::UnitZ();
        if (kinematics::checkToolPose(machine.model, nom, target).ok())
          out.push_back(
              {target.position, kinematics::jointsOf(nom), kinematics::configurationOf(nom)});
      }
  return out;
}

/// Over the working-box grid: "before", the tool-point error of the nominal controller on the
/// calibrated machine (nominal IK, calibrated FK: what the calibration removes), and "after", the
/// linearised tool-point uncertainty the calibration leaves (exechonTargetUncertainty with the
/// estimate's covariance).
std::optional<ordered_json> workspaceMap(const io::ExechonMachine& machine,
                                         const kinematics::ExechonModel& calibrated,
                                         const Eigen::MatrixXd& covariance) {
  std::vector<double> errors, uncertainty;
  kinematics::ExechonData cal_data(calibrated);
  for (const GridPoint& g : workingBoxGrid(machine)) {
    if (!kinematics::toolForwardKinematics(calibrated, cal_data, g.joints, g.seed, machine.fk).ok())
      continue;
    errors.push_back((cal_data.world_p_tool - g.position).norm());
    if (const auto u = cal::exechonTargetUncertainty(
            calibrated, covariance, g.joints, Eigen::Vector3d::Zero(), g.seed, machine.fk))
      uncertainty.push_back(*u);
  }
  const auto before = statisticsJson(errors);
  if (!before) return std::nullopt;
  ordered_json out{{"before", *before}};
  if (const auto after = statisticsJson(uncertainty)) out["after"] = *after;
  return out;
}

/// The joints of the working-box grid, or, without a working box, the joints of the fitted
/// observations: where the Monte Carlo tool-point spread is evaluated.
std::vector<kinematics::ExechonJoints> monteCarloWorkspace(
    const io::ExechonMachine& machine, const cal::ExechonCalibrationData& data) {
  std::vector<kinematics::ExechonJoints> out;
  for (const GridPoint& g : workingBoxGrid(machine)) out.push_back(g.joints);
  if (out.empty())
    for (const cal::ExechonObservation& o : data.observations) out.push_back(o.joints);
  return out;
}

ordered_json toJson(const cal::TcpErrorStatistics& s) {
  return {{"samples", s.samples}, {"mean", s.mean}, {"p95", s.p95}, {"max", s.max}};
}

/// --monte-carlo: the calibration repeated on simulated tracker noise (monteCarloExechon); fills
/// j["monte_carlo"] and a line of `t`.
void monteCarlo(const ExechonArgs& args,
                const io::ExechonMachine& machine,
                const cal::ExechonCalibrationData& data,
                const cal::ExechonCalibrationSummary& s,
                const kinematics::ExechonModel& estimate,
                const cal::ExechonCalibrationOptions& options,
                ordered_json& j,
                std::string& t) {
  cal::ExechonMonteCarloOptions mc;
  mc.trials = args.monte_carlo;
  mc.threads = args.threads;
  mc.position_sigma = args.sigma_position > 0.0 ? args.sigma_position : s.sigma;
  mc.direction_sigma = args.sigma_orientation_urad * 1e-6;
  const bool tty = ::isatty(STDERR_FILENO) != 0;
  mc.progress = [tty](int done, int total) {
    if (tty) fmt::print(stderr, "\rpkm: Monte Carlo {}/{}", done, total);
  };
  const cal::ExechonMonteCarloSummary u = cal::monteCarloExechon(machine.model,
                                                                 data,
                                                                 estimate,
                                                                 s.measurement_frame,
                                                                 monteCarloWorkspace(machine, data),
                                                                 options,
                                                                 mc);
  if (tty) fmt::print(stderr, "\n");
  ordered_json m;
  m["trials"] = u.trials;
  m["failures"] = u.failures;
  m["not_converged"] = u.not_converged;
  m["seconds"] = u.seconds;
  m["sigma_position"] = mc.position_sigma;
  m["sigma_orientation"] = mc.direction_sigma;
  m["configurations"] = u.configurations;
  m["tool_sigma"] = toJson(u.tool_sigma);
  m["tool_deviation"] = toJson(u.tcp);
  m["parameter_sigma"] = std::vector<double>(u.standard_deviation.data(),
                                             u.standard_deviation.data() + cal::kExechonParameters);
  if (s.measurement_frame)
    m["frame_sigma"] = std::vector<double>(u.frame_standard_deviation.data(),
                                           u.frame_standard_deviation.data() + 6);
  j["monte_carlo"] = m;
  t += fmt::format(
      "tool-point spread after calibration (Monte Carlo, {} trials, {} failed, {} configurations): "
      "mean {:.6g}, 95 % {:.6g}, max {:.6g}\n",
      u.trials,
      u.failures,
      u.configurations,
      u.tool_sigma.mean,
      u.tool_sigma.p95,
      u.tool_sigma.max);
}

/// The tripod and wrist from the PKM tracker files: fills `result`, `j` and the report `t`.
void fitTripod(const ExechonArgs& args,
               const io::ExechonMachine& machine,
               io::ExechonCalibrationInput& input,
               const io::ExechonCalibrationInput& held,
               io::ExechonMachine& result,
               ordered_json& j,
               std::string& t) {
  const Eigen::Vector3d target = input.data.target_offset;
  const bool use_frame = args.frame == "tracker" || (args.frame == "auto" && input.tracker_frame);
  cal::ExechonCalibrationOptions options;
  options.fk = machine.fk;
  if (use_frame) {
    input.data.measurement_frame =
        cal::initialExechonMeasurementFrame(machine.model, input.data, machine.fk);
    // The tracker frame and the base placement differ by one rigid motion the data cannot see:
    // the machine's world frame stays where the machine file puts the base (docs/calibration.md).
    for (int k = cal::kExechonBaseParameter; k < cal::kExechonParameters; ++k)
      options.free[static_cast<std::size_t>(k)] = false;
  }
  for (const std::string& name : args.fix)
    options.free[static_cast<std::size_t>(cal::exechonParameterIndex(name))] = false;
  if (args.loss == "huber") options.loss = cal::RobustLoss::kHuber;
  if (args.loss == "cauchy") options.loss = cal::RobustLoss::kCauchy;
  options.loss_scale = args.loss_scale;

  const cal::ExechonCalibrationSummary s =
      cal::calibrateExechon(machine.model, input.data, options);
  const double scale = machine.model.characteristicLength();
  if (!s.warnings.empty())
    throw InvalidArgument(
        fmt::format("calibration result is implausible; nothing was written:\n  {}",
                    fmt::join(s.warnings, "\n  ")));
  if (!(s.after.rms < 1e-3 * scale)) {
    std::string worst;
    for (const auto& w : s.worst) worst += fmt::format("\n  {}: {:.4g}", w.source, w.residual);
    throw InvalidArgument(fmt::format(
        "calibration does not explain the data: residual RMS {:.4g} (max {:.4g}) after {} "
        "iterations ({}); check the units (legs {}, wrist angles in degrees), the --frame option "
        "and outliers (--loss cauchy --loss-scale ...); nothing was written. Largest residuals:{}",
        s.after.rms,
        s.after.max,
        s.iterations,
        s.termination,
        toString(machine.model.unit),
        worst));
  }
  result.model =
      cal::withExechonParameters(machine.model, s.parameters, machine.model.world_T_zoppi);
  result.model.name = machine.model.name + "-calibrated";
  result.notices.clear();
  result.description = fmt::format("{} calibrated by pkm calibrate exechon", machine.model.name);

  j["observations"] = {{"points", input.data.observations.size()},
                       {"equations", input.data.equations()}};
  j["target_offset"] = {target.x(), target.y(), target.z()};
  j["solver"] = {{"converged", s.converged},
                 {"termination", s.termination},
                 {"iterations", s.iterations},
                 {"initial_cost", s.initial_cost},
                 {"final_cost", s.final_cost},
                 {"seconds", s.seconds}};
  j["residuals"] = {{"before", toJson(s.before)}, {"after", toJson(s.after)}};
  if (!held.data.observations.empty()) {
    std::optional<geometry::RigidTransform> f0;
    if (use_frame) f0 = input.data.measurement_frame;
    j["holdout"] = {{"before", holdout(machine.model, f0, held.data, machine.fk)},
                    {"after", holdout(result.model, s.measurement_frame, held.data, machine.fk)}};
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
  ordered_json worst = ordered_json::array();
  for (const auto& w : s.worst) worst.push_back({{"source", w.source}, {"residual", w.residual}});
  j["worst_observations"] = worst;
  if (const auto map = workspaceMap(machine, result.model, s.covariance)) j["tcp_error_map"] = *map;
  std::string mc_text;
  if (args.monte_carlo > 0)
    monteCarlo(args, machine, input.data, s, result.model, options, j, mc_text);
  ordered_json params = ordered_json::array();
  for (int k = 0; k < cal::kExechonParameters; ++k)
    params.push_back(
        {{"name", cal::exechonParameterName(k)},
         {"unit", cal::exechonParameterIsLength(k) ? toString(machine.model.unit) : "rad"},
         {"free", options.free[static_cast<std::size_t>(k)]},
         {"initial", s.initial(k)},
         {"estimate", s.parameters(k)},
         {"change", s.parameters(k) - s.initial(k)},
         {"sigma", s.standard_deviation(k)}});
  j["parameters"] = params;
  t += fmt::format("calibrated {} from {} equations ({} tracker points)\n",
                   machine.model.name,
                   input.data.equations(),
                   input.data.observations.size());
  t += fmt::format("solver: {} iterations, {:.3f} s, {}\n",
                   s.iterations,
                   s.seconds,
                   s.converged ? "converged" : s.termination);
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
                   toString(machine.model.unit),
                   s.before.rms,
                   s.after.rms,
                   s.before.max,
                   s.after.max);
  if (j.contains("holdout"))
    t += fmt::format("held-out target error: RMS {:.6g} -> {:.6g}, max {:.6g} -> {:.6g}\n",
                     j["holdout"]["before"]["rms"].get<double>(),
                     j["holdout"]["after"]["rms"].get<double>(),
                     j["holdout"]["before"]["max"].get<double>(),
                     j["holdout"]["after"]["max"].get<double>());
  if (!s.worst.empty())
    t += fmt::format("largest residual after the fit: {} ({:.4g})\n",
                     s.worst.front().source,
                     s.worst.front().residual);
  if (j.contains("tcp_error_map"))
    t += fmt::format(
        "working-volume tool error of the nominal controller (what calibration removes): mean "
        "{:.6g}, 95 % {:.6g}, max {:.6g}\n",
        j["tcp_error_map"]["before"]["mean"].get<double>(),
        j["tcp_error_map"]["before"]["p95"].get<double>(),
        j["tcp_error_map"]["before"]["max"].get<double>());
  if (j.contains("tcp_error_map") && j["tcp_error_map"].contains("after"))
    t += fmt::format(
        "working-volume tool uncertainty after calibration (linearised covariance): mean {:.6g}, "
        "95 % {:.6g}, max {:.6g}\n",
        j["tcp_error_map"]["after"]["mean"].get<double>(),
        j["tcp_error_map"]["after"]["p95"].get<double>(),
        j["tcp_error_map"]["after"]["max"].get<double>());
  t += mc_text;
}

/// CAL.errors.json for --out CAL.json.
std::string errorsOutput(const std::string& out) {
  std::string stem = out;
  if (stem.size() > 5 && stem.ends_with(".json")) stem.resize(stem.size() - 5);
  return stem + ".errors.json";
}

/// The tripod errors of `calibrated` against `nominal` (the parameters before the base placement).
sim::ExechonTripodErrors tripodDifference(const kinematics::ExechonModel& nominal,
                                          const kinematics::ExechonModel& calibrated) {
  const cal::ExechonParameterVector d = cal::exechonParameters(calibrated, nominal.world_T_zoppi) -
                                        cal::exechonParameters(nominal, nominal.world_T_zoppi);
  sim::ExechonTripodErrors e;
  e.dA = d(0);
  e.dB = d(1);
  e.dC = d(2);
  e.l12A = d(3);
  e.l12C = d(4);
  e.l12B = d(5);
  e.l23B = d(6);
  e.pA = d(7);
  e.pB = d(8);
  e.pC = d(9);
  e.hA = d(10);
  e.hC = d(11);
  e.hx = d(12);
  e.hz = d(13);
  e.length_offset = d.segment<3>(cal::kExechonOffsetParameter);
  e.c0 = d(cal::kExechonWristParameter);
  e.a0 = d(cal::kExechonWristParameter + 1);
  e.tool_length = d(cal::kExechonWristParameter + 2);
  return e;
}

ordered_json squarenessJson(const kinematics::HybridSquareness& s) {
  return {{"szX2", s.sz_x2}, {"sxP", s.sx_p}, {"syP", s.sy_p}, {"szP", s.sz_p}};
}

/// Target errors |predicted − measured (in frame)| over held-out hybrid data.
ordered_json hybridHoldout(const kinematics::HybridMachineModel& model,
                           const kinematics::GeometricErrors& known,
                           const kinematics::HybridSquareness& squareness,
                           const cal::HybridCalibrationData& data,
                           const std::optional<geometry::RigidTransform>& frame,
                           const cal::TripodMotion& tripod) {
  double sum = 0.0, worst = 0.0;
  int n = 0;
  for (const cal::HybridObservation& o : data.observations) {
    const auto p =
        cal::hybridTarget(model, known, squareness, o.command, data.target_offset, tripod);
    if (!p) continue;
    const Eigen::Vector3d m =
        frame ? Eigen::Vector3d(frame->rotation * o.point + frame->translation) : o.point;
    const double e = (m - *p).norm();
    sum += e * e;
    worst = std::max(worst, e);
    ++n;
  }
  return {{"poses", n}, {"rms", n > 0 ? std::sqrt(sum / n) : 0.0}, {"max", worst}};
}

/// The rigid fit of the measured points to the targets `squareness` predicts (a frame start).
geometry::RigidTransform hybridFrameStart(const kinematics::HybridMachineModel& model,
                                          const kinematics::GeometricErrors& known,
                                          const kinematics::HybridSquareness& squareness,
                                          const cal::HybridCalibrationData& data,
                                          const cal::TripodMotion& tripod) {
  std::vector<Eigen::Vector3d> work, measured;
  for (const cal::HybridObservation& o : data.observations)
    if (const auto p =
            cal::hybridTarget(model, known, squareness, o.command, data.target_offset, tripod)) {
      work.push_back(*p);
      measured.push_back(o.point);
    }
  if (work.size() < 3) throw InvalidArgument("hybrid data: fewer than 3 reachable commands");
  return geometry::fitRigidTransform(work, measured);
}

/// The four squareness errors from the hybrid tracker files, with the calibrated tripod's error
/// motion when the PKM was calibrated too: fills j["hybrid"] (with the errors file text) and `t`.
void fitSquareness(const ExechonArgs& args,
                   const io::ExechonMachine& machine,
                   const io::ExechonMachine& result,
                   io::ExechonCalibrationInput& input,
                   io::ExechonCalibrationInput& held,
                   ordered_json& j,
                   std::string& t) {
  if (!machine.hybrid)
    throw InvalidArgument(
        fmt::format("hybrid tracker data needs a machine with a \"hybrid\" section; '{}' has none",
                    machine.model.name));
  const kinematics::HybridMachineModel& model = *machine.hybrid;
  kinematics::GeometricErrors known;
  if (!args.errors.empty()) known = io::loadGeometricErrors(args.errors);
  known.squareness = {};
  std::optional<sim::HybridTripod> tripod;
  const sim::ExechonTripodErrors diff = tripodDifference(machine.model, result.model);
  if (!diff.isZero()) tripod.emplace(machine.model, diff, machine.fk);
  cal::TripodMotion motion;
  if (tripod)
    motion = [&tripod](const Eigen::Vector3d& p) -> std::optional<Eigen::Isometry3d> {
      try {
        return tripod->errorMotion(p);
      } catch (const InvalidArgument&) {
        return std::nullopt;
      }
    };
  cal::HybridCalibrationData& d = input.hybrid;
  std::optional<geometry::RigidTransform> before_frame;
  if (d.measurement_frame) {
    d.measurement_frame = hybridFrameStart(model, known, {}, d, motion);
    before_frame = d.measurement_frame;
  }
  cal::HybridCalibrationOptions options;
  if (args.loss == "huber") options.loss = cal::RobustLoss::kHuber;
  if (args.loss == "cauchy") options.loss = cal::RobustLoss::kCauchy;
  options.loss_scale = args.loss_scale;
  const cal::HybridCalibrationSummary s =
      cal::calibrateHybridSquareness(model, known, d, options, motion);
  if (!(s.after.rms < 1e-3 * machine.model.characteristicLength())) {
    std::string worst;
    for (const auto& w : s.worst) worst += fmt::format("\n  {}: {:.4g}", w.source, w.residual);
    throw InvalidArgument(fmt::format(
        "squareness calibration does not explain the hybrid data: residual RMS {:.4g} (max "
        "{:.4g}); check the units, --errors and outliers; nothing was written. Largest "
        "residuals:{}",
        s.after.rms,
        s.after.max,
        worst));
  }
  kinematics::GeometricErrors estimated = known;
  estimated.squareness = s.squareness;
  ordered_json h;
  h["observations"] = d.observations.size();
  h["known_errors"] = args.errors.empty() ? "none" : args.errors;
  h["tripod_error_motion"] = tripod.has_value();
  h["squareness"] = squarenessJson(s.squareness);
  h["sigma"] = {{"szX2", s.standard_deviation(0)},
                {"sxP", s.standard_deviation(1)},
                {"syP", s.standard_deviation(2)},
                {"szP", s.standard_deviation(3)}};
  h["solver"] = {{"converged", s.converged},
                 {"termination", s.termination},
                 {"iterations", s.iterations},
                 {"seconds", s.seconds}};
  h["residuals"] = {{"before", toJson(s.before)}, {"after", toJson(s.after)}};
  h["identifiability"] = {{"parameters", s.identifiability.parameters},
                          {"rank", s.identifiability.rank},
                          {"condition_number", s.identifiability.condition_number}};
  if (s.measurement_frame) h["measurement_frame"] = frameJson(*s.measurement_frame);
  ordered_json worst = ordered_json::array();
  for (const auto& w : s.worst) worst.push_back({{"source", w.source}, {"residual", w.residual}});
  h["worst_observations"] = worst;
  if (!held.hybrid.observations.empty()) {
    // A held-out file without `smr offset mm` is taken to carry the fitted files' target.
    held.hybrid.target_offset = held.hybrid_target_offset.value_or(d.target_offset);
    h["holdout"] = {
        {"before", hybridHoldout(model, known, {}, held.hybrid, before_frame, {})},
        {"after",
         hybridHoldout(model, known, s.squareness, held.hybrid, s.measurement_frame, motion)}};
  }
  h["errors_file"] = io::writeGeometricErrorsJson(estimated);
  j["hybrid"] = h;
  constexpr double kMrad = 1e3;
  t += fmt::format(
      "squareness from {} hybrid observations{}: szX2 {:.4f}, sxP {:.4f}, syP {:.4f}, szP {:.4f} "
      "mrad (sigma {:.2g}, {:.2g}, {:.2g}, {:.2g})\n",
      d.observations.size(),
      tripod ? " (with the calibrated tripod)" : "",
      kMrad * s.squareness.sz_x2,
      kMrad * s.squareness.sx_p,
      kMrad * s.squareness.sy_p,
      kMrad * s.squareness.sz_p,
      kMrad * s.standard_deviation(0),
      kMrad * s.standard_deviation(1),
      kMrad * s.standard_deviation(2),
      kMrad * s.standard_deviation(3));
  t += fmt::format("hybrid residuals ({}): RMS {:.6g} -> {:.6g}, max {:.6g} -> {:.6g}\n",
                   toString(machine.model.unit),
                   s.before.rms,
                   s.after.rms,
                   s.before.max,
                   s.after.max);
  if (h.contains("holdout"))
    t += fmt::format("held-out hybrid target error: RMS {:.6g} -> {:.6g}, max {:.6g} -> {:.6g}\n",
                     h["holdout"]["before"]["rms"].get<double>(),
                     h["holdout"]["after"]["rms"].get<double>(),
                     h["holdout"]["before"]["max"].get<double>(),
                     h["holdout"]["after"]["max"].get<double>());
}

void runExechon(const ExechonArgs& args) {
  io::ExechonMachine machine = io::loadExechonMachine(args.machine);
  printNotices(machine.notices);
  const workflow::CalibrationOutputs paths = workflow::calibrationOutputs(args.out);
  const std::string errors_path = errorsOutput(args.out);
  io::ExechonCalibrationInput input, held;
  for (const std::string& f : args.data) io::addExechonCalibrationFile(f, input);
  for (const std::string& f : args.holdout) io::addExechonCalibrationFile(f, held);
  printNotices(input.notes);
  const bool hybrid = !input.hybrid.observations.empty();
  if (!args.force)
    for (const std::string& p : {paths.machine, paths.summary, errors_path})
      if ((p != errors_path || hybrid) && std::filesystem::exists(p))
        throw IoError(fmt::format("{} exists; pass --force to overwrite it", p));
  Eigen::Vector3d target = input.target_offset.value_or(Eigen::Vector3d::Zero());
  if (!args.target_offset.empty()) {
    if (args.target_offset.size() != 3) throw InvalidArgument("--target-offset needs x,y,z");
    target = Eigen::Vector3d(args.target_offset[0], args.target_offset[1], args.target_offset[2]);
  }
  input.data.target_offset = target;
  held.data.target_offset = held.target_offset.value_or(target);

  io::ExechonMachine result = machine;
  ordered_json j;
  j["machine"] = machine.model.name;
  j["units"] = toString(machine.model.unit);
  j["data"] = input.notes;
  std::string t;
  if (!input.data.observations.empty()) fitTripod(args, machine, input, held, result, j, t);
  std::vector<std::string> written{paths.machine, paths.summary};
  if (hybrid) {
    fitSquareness(args, machine, result, input, held, j, t);
    written.push_back(errors_path);
  }
  j["outputs"] = {{"machine", paths.machine}, {"summary", paths.summary}};
  if (hybrid) j["outputs"]["errors"] = errors_path;
  constexpr io::Overwrite kReplace = io::Overwrite::kAllow;  // checked above
  io::writeFileAtomic(paths.machine, io::writeExechonJson(result), kReplace);
  if (hybrid)
    io::writeFileAtomic(errors_path, j["hybrid"]["errors_file"].get<std::string>(), kReplace);
  if (hybrid) j["hybrid"].erase("errors_file");
  io::writeFileAtomic(paths.summary, j.dump(2) + "\n", kReplace);
  if (!args.db.empty()) {
    std::vector<std::pair<std::string, std::string>> comps{{"machine-json", paths.machine}};
    if (hybrid) comps.emplace_back("errors-json", errors_path);
    workflow::recordCalibration(args.db,
                                {machine.model.name,
                                 machine.hybrid ? "hybrid" : "exechon",
                                 "calibrate exechon",
                                 args.data,
                                 j.dump(2) + "\n",
                                 std::string(toString(machine.model.unit)),
                                 comps});
  }
  if (args.json) {
    printJson(j);
    return;
  }
  Output out;
  out.text() = t + fmt::format("wrote {}\n", fmt::join(written, ", "));
}

}  // namespace

ordered_json frameJson(const geometry::RigidTransform& f) {
  const Eigen::Vector3d rpy = geometry::rpyFromRotation(f.rotation);
  return {{"position", {f.translation.x(), f.translation.y(), f.translation.z()}},
          {"rpy_deg", {radToDeg(rpy.x()), radToDeg(rpy.y()), radToDeg(rpy.z())}}};
}

void addCalibrateExechon(CLI::App& calibrate) {
  auto args = std::make_shared<ExechonArgs>();
  CLI::App* ex = calibrate.add_subcommand(
      "exechon", "calibrate an Exechon (tripod and wrist) from laser-tracker files");
  ex->add_option("--machine", args->machine, "Exechon machine file or built-in name")
      ->capture_default_str();
  ex->add_option("--data",
                 args->data,
                 "Exechon tracker files (q0,q1,q2,c,a,x,y,z[,i,j,k]) and hybrid tracker files "
                 "(x2,y2,xp,yp,zp,x,y,z)")
      ->required()
      ->check(CLI::ExistingFile);
  ex->add_option("--holdout", args->holdout, "tracker files kept out of the fit, for validation")
      ->check(CLI::ExistingFile);
  ex->add_option("--out", args->out, "calibrated machine file CAL.json (also CAL.summary.json)")
      ->required();
  ex->add_option("--frame",
                 args->frame,
                 "where tracker readings are: auto (from the files' metadata), world, tracker")
      ->check(CLI::IsMember({"auto", "world", "tracker"}));
  ex->add_option("--target-offset",
                 args->target_offset,
                 "the tracker target in the tool frame x,y,z (default: the files' smr offset)")
      ->delimiter(',')
      ->expected(3);
  ex->add_option("--fix", args->fix, "parameters held at their initial value (e.g. tripod.hx)")
      ->delimiter(',');
  ex->add_option("--loss", args->loss, "robust loss: none, huber, cauchy")
      ->check(CLI::IsMember({"none", "huber", "cauchy"}));
  ex->add_option("--loss-scale", args->loss_scale, "robust loss scale, machine unit");
  ex->add_option("--errors",
                 args->errors,
                 "hybrid machines: the known geometric errors (PDGE tables; file or built-in) "
                 "under the squareness fit")
      ->capture_default_str();
  ex->add_option("--db", args->db, "also record the calibration in this result store (pkm.db)");
  ex->add_option("--monte-carlo",
                 args->monte_carlo,
                 "also run N Monte Carlo trials of the tripod calibration under simulated noise")
      ->check(CLI::Range(2, 100000));
  ex->add_option(
      "--sigma-position",
      args->sigma_position,
      "Monte Carlo: tracker point noise, machine unit (default: the fitted residual sigma)");
  ex->add_option("--sigma-orientation",
                 args->sigma_orientation_urad,
                 "Monte Carlo: tool-direction noise, urad (default 0)");
  ex->add_option("--threads", args->threads, "Monte Carlo worker threads (default: all cores)");
  ex->add_flag("--force", args->force, "overwrite existing output files");
  ex->add_flag("--json", args->json, "print the summary as JSON");
  ex->callback([args] { runExechon(*args); });
}

}  // namespace pkm::cli
