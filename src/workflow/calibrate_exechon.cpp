// `pkm calibrate exechon` as a workflow (workflow/calibrate_exechon.hpp): the request, the
// output files and the hybrid squareness fit; the tripod fit is in calibrate_exechon_tripod.cpp.
#include "pkm/workflow/calibrate_exechon.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "calibrate_exechon_detail.hpp"
#include "calibration_common.hpp"
#include "pkm/calibration/acceptance.hpp"
#include "pkm/calibration/exechon_parameters.hpp"
#include "pkm/calibration/hybrid_calibration.hpp"
#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/geometric_errors.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/simulation/hybrid_tripod_errors.hpp"
#include "pkm/workflow/calibrate_hexapod.hpp"
#include "pkm/workflow/calibration_record.hpp"

namespace pkm::workflow {
namespace {

namespace cal = pkm::calibration;
namespace sim = pkm::simulation;

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

/// Throws when the squareness fit does not explain the hybrid data.
void acceptSquareness(const cal::HybridCalibrationSummary& s, double characteristic_length) {
  if (cal::explainsData(s.after.rms, characteristic_length)) return;
  throw InvalidArgument(fmt::format(
      "squareness calibration does not explain the hybrid data: residual RMS {:.4g} (max "
      "{:.4g}); check the units, --errors and outliers; nothing was written. Largest "
      "residuals:{}",
      s.after.rms,
      s.after.max,
      detail::worstList(s.worst)));
}

/// The error motion of `tripod` as the squareness fit takes it (nullopt outside its reach).
cal::TripodMotion motionOf(const std::optional<sim::HybridTripod>& tripod) {
  if (!tripod) return {};
  return [&tripod](const Eigen::Vector3d& p) -> std::optional<geometry::RigidTransform> {
    try {
      return tripod->errorMotion(p);
    } catch (const InvalidArgument&) {
      return std::nullopt;
    }
  };
}

/// The squareness's standard uncertainty from the calibrated tripod's covariance Σ_θ (26 × 26):
/// the fit repeated with the tripod moved by 1σ along each principal direction of Σ_θ (GUM §5.1.3
/// sensitivities by re-evaluation), u² = Σ_k (Δs_k)². Zero without a covariance.
Eigen::Vector4d tripodSquarenessSpread(const io::ExechonMachine& machine,
                                       const kinematics::ExechonModel& calibrated,
                                       const Eigen::MatrixXd& covariance,
                                       const kinematics::GeometricErrors& known,
                                       const cal::HybridCalibrationData& data,
                                       const cal::HybridCalibrationOptions& options,
                                       const kinematics::HybridSquareness& estimate) {
  Eigen::Vector4d variance = Eigen::Vector4d::Zero();
  if (covariance.rows() != cal::kExechonParameters) return variance;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(covariance);
  const double top = eig.eigenvalues().maxCoeff();
  const cal::ExechonParameterVector theta =
      cal::exechonParameters(calibrated, machine.model.world_T_zoppi);
  for (Eigen::Index k = 0; k < eig.eigenvalues().size(); ++k) {
    const double lambda = eig.eigenvalues()(k);
    if (!(lambda > 1e-12 * top)) continue;
    const cal::ExechonParameterVector moved = theta + std::sqrt(lambda) * eig.eigenvectors().col(k);
    std::optional<sim::HybridTripod> tripod;
    tripod.emplace(machine.model,
                   tripodDifference(
                       machine.model,
                       cal::withExechonParameters(calibrated, moved, machine.model.world_T_zoppi)),
                   machine.fk);
    try {
      const kinematics::HybridSquareness s =
          cal::calibrateHybridSquareness(*machine.hybrid, known, data, options, motionOf(tripod))
              .squareness;
      const Eigen::Vector4d d(s.sz_x2 - estimate.sz_x2,
                              s.sx_p - estimate.sx_p,
                              s.sy_p - estimate.sy_p,
                              s.sz_p - estimate.sz_p);
      variance += d.cwiseProduct(d);
    } catch (const InvalidArgument&) {
      // A moved tripod the data cannot follow: its direction is left out.
    }
  }
  return variance.cwiseSqrt();
}

/// The four squareness errors from the hybrid tracker files, with the calibrated tripod's error
/// motion when the PKM was calibrated too (and its covariance carried into the squareness's
/// uncertainty); returns the estimated errors (CAL.errors.json).
kinematics::GeometricErrors fitSquareness(const ExechonCalibrationRequest& r,
                                          const io::ExechonMachine& machine,
                                          const io::ExechonMachine& calibrated,
                                          const Eigen::MatrixXd& tripod_covariance,
                                          io::ExechonCalibrationInput& input,
                                          io::ExechonCalibrationInput& held,
                                          io::HybridSquarenessReport& report) {
  if (!machine.hybrid)
    throw InvalidArgument(
        fmt::format("hybrid tracker data needs a machine with a \"hybrid\" section; '{}' has none",
                    machine.model.name));
  const kinematics::HybridMachineModel& model = *machine.hybrid;
  kinematics::GeometricErrors known;
  if (!r.errors.empty()) known = io::loadGeometricErrors(r.errors);
  known.squareness = {};
  std::optional<sim::HybridTripod> tripod;
  const sim::ExechonTripodErrors diff = tripodDifference(machine.model, calibrated.model);
  if (!diff.isZero()) tripod.emplace(machine.model, diff, machine.fk);
  const cal::TripodMotion motion = motionOf(tripod);
  cal::HybridCalibrationData& d = input.hybrid;
  std::optional<geometry::RigidTransform> before_frame;
  if (d.measurement_frame) {
    d.measurement_frame = cal::initialHybridMeasurementFrame(model, known, {}, d, motion);
    before_frame = d.measurement_frame;
  }
  cal::HybridCalibrationOptions options;
  options.loss = detail::robustLoss(r.loss);
  options.loss_scale = r.loss_scale;
  report.fit = cal::calibrateHybridSquareness(model, known, d, options, motion);
  const cal::HybridCalibrationSummary& s = report.fit;
  acceptSquareness(s, machine.model.characteristicLength());
  if (tripod) {
    // The re-fits start from the fitted frame: each moves the estimate a little.
    cal::HybridCalibrationData start = d;
    if (start.measurement_frame) start.measurement_frame = s.measurement_frame;
    report.tripod_standard_uncertainty = tripodSquarenessSpread(
        machine, calibrated.model, tripod_covariance, known, start, options, s.squareness);
  }
  report.observations = d.observations.size();
  report.known_errors = r.errors.empty() ? "none" : r.errors;
  report.tripod_error_motion = tripod.has_value();
  if (!held.hybrid.observations.empty()) {
    // A held-out file without `smr offset mm` is taken to carry the fitted files' target.
    held.hybrid.target_offset = held.hybrid_target_offset.value_or(d.target_offset);
    report.holdout = io::HoldoutComparison{
        cal::hybridHoldoutErrors(model, known, {}, held.hybrid, before_frame, {}),
        cal::hybridHoldoutErrors(
            model, known, s.squareness, held.hybrid, s.measurement_frame, motion)};
  }
  kinematics::GeometricErrors estimated = known;
  estimated.squareness = s.squareness;
  return estimated;
}

/// Reads the data and held-out files and sets their target offsets.
void readInput(const ExechonCalibrationRequest& r,
               io::ExechonCalibrationInput& input,
               io::ExechonCalibrationInput& held,
               const RunControl& control) {
  for (const io::NamedText& f : r.data) io::addExechonCalibrationFile(f, input);
  for (const io::NamedText& f : r.holdout) io::addExechonCalibrationFile(f, held);
  std::vector<std::string> frameless = input.frameless;
  frameless.insert(frameless.end(), held.frameless.begin(), held.frameless.end());
  detail::refuseUnstatedFrame(r.frame, frameless);
  control.note(input.notes);
}

/// Refuses (pkm::IoError) when one of the output files of `out` exists and not `force`.
void checkOutputs(const std::string& out, bool hybrid, bool force) {
  const io::Overwrite overwrite = force ? io::Overwrite::kAllow : io::Overwrite::kRefuse;
  io::checkOverwrite(calibrationOutputs(out).machine, overwrite);
  io::checkOverwrite(calibrationOutputs(out).summary, overwrite);
  if (hybrid) io::checkOverwrite(calibrationErrorsOutput(out), overwrite);
}

}  // namespace

cal::RobustLoss detail::robustLoss(const std::string& name) {
  if (name == "huber") return cal::RobustLoss::kHuber;
  if (name == "cauchy") return cal::RobustLoss::kCauchy;
  return cal::RobustLoss::kNone;
}

void ExechonCalibrationRequest::validate() const {
  detail::checkCalibrationRequest(data, "tracker file", out, db, frame, loss, monte_carlo);
}

std::string calibrationErrorsOutput(const std::string& out) {
  std::string stem = out;
  if (stem.size() > 5 && stem.ends_with(".json")) stem.resize(stem.size() - 5);
  return stem + ".errors.json";
}

ExechonCalibrationResult calibrateExechon(const ExechonCalibrationRequest& r,
                                          const RunControl& control) {
  r.validate();
  const io::ExechonMachine machine = r.loaded ? *r.loaded : io::loadExechonMachine(r.machine);
  control.note(machine.notices);
  io::ExechonCalibrationInput input, held;
  readInput(r, input, held, control);
  const bool hybrid = !input.hybrid.observations.empty();
  if (!r.out.empty()) checkOutputs(r.out, hybrid, r.force);
  const Eigen::Vector3d target =
      r.target_offset.value_or(input.target_offset.value_or(Eigen::Vector3d::Zero()));
  input.data.target_offset = target;
  held.data.target_offset = held.target_offset.value_or(target);

  ExechonCalibrationResult result;
  io::ExechonCalibrationReport& rep = result.report;
  result.calibrated = machine;
  rep.machine = machine.model.name;
  rep.unit = machine.model.unit;
  rep.data_notes = input.notes;
  if (!input.data.observations.empty())
    rep.tripod = detail::fitTripod(r, machine, input, held, result.calibrated, control);
  if (hybrid) {
    rep.hybrid.emplace();
    result.errors_json = io::writeGeometricErrorsJson(fitSquareness(
        r,
        machine,
        result.calibrated,
        rep.tripod && rep.tripod->uncertainty ? rep.tripod->uncertainty->parameters.covariance
                                              : Eigen::MatrixXd(),
        input,
        held,
        *rep.hybrid));
  }
  result.summary_json = io::exechonCalibrationJson(rep);
  if (r.out.empty()) return result;
  writeExechonCalibration(result, r.out, r.force);
  const CalibrationOutputs paths = calibrationOutputs(r.out);
  const std::string errors_path = calibrationErrorsOutput(r.out);
  if (!r.db.empty()) {
    std::vector<std::pair<std::string, std::string>> comps{{"machine-json", paths.machine}};
    if (hybrid) comps.emplace_back("errors-json", errors_path);
    recordCalibration(r.db,
                      {machine.model.name,
                       machine.hybrid ? "hybrid" : "exechon",
                       "calibrate exechon",
                       detail::inputNames(r.data),
                       result.summary_json,
                       std::string(toString(machine.model.unit)),
                       comps});
  }
  return result;
}

void writeExechonCalibration(ExechonCalibrationResult& result, const std::string& out, bool force) {
  PKM_CHECK(!out.empty(), "give the calibrated machine file CAL.json");
  const bool hybrid = result.report.hybrid.has_value();
  checkOutputs(out, hybrid, force);
  const CalibrationOutputs paths = calibrationOutputs(out);
  const std::string errors_path = calibrationErrorsOutput(out);
  io::ExechonCalibrationReport& rep = result.report;
  rep.out_machine = paths.machine;
  rep.out_summary = paths.summary;
  rep.out_errors = hybrid ? errors_path : "";
  result.summary_json = io::exechonCalibrationJson(rep);
  const io::Overwrite overwrite = force ? io::Overwrite::kAllow : io::Overwrite::kRefuse;
  io::writeFileAtomic(paths.machine, io::writeExechonJson(result.calibrated), overwrite);
  if (hybrid) io::writeFileAtomic(errors_path, result.errors_json, overwrite);
  io::writeFileAtomic(paths.summary, result.summary_json, overwrite);
  result.written = {paths.machine, paths.summary};
  if (hybrid) result.written.push_back(errors_path);
}

}  // namespace pkm::workflow
