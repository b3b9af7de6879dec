#include "pkm/compensation/predistortion.hpp"

#include "pkm/core/error.hpp"
#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::compensation {
namespace {

void checkModels(const kinematics::HexapodModel& nominal,
                 const kinematics::HexapodModel& calibrated,
                 const PredistortionOptions& options) {
  nominal.validate();
  calibrated.validate();
  PKM_CHECK(nominal.unit == calibrated.unit,
            "pre-distortion: the nominal and calibrated models use different length units");
  std::string why;
  PKM_CHECK(options.fk.isValid(&why), "pre-distortion: invalid FK options: {}", why);
}

void checkPose(const kinematics::PoseRpy& pose, const char* what) {
  PKM_CHECK(
      pose.position.allFinite() && pose.rpy.allFinite(), "pre-distortion: {} is not finite", what);
}

/// IK_calibrated then FK_nominal with preallocated workspaces.
PredistortionResult solve(const kinematics::HexapodModel& nominal,
                          const kinematics::HexapodModel& calibrated,
                          kinematics::HexapodData& nominal_data,
                          kinematics::HexapodData& calibrated_data,
                          const kinematics::PoseRpy& desired,
                          const kinematics::PoseRpy& seed,
                          const PredistortionOptions& options) {
  checkPose(desired, "the desired pose");
  checkPose(seed, "the FK seed");
  PredistortionResult r;
  r.readings = kinematics::inverseKinematics(calibrated, calibrated_data, desired);
  r.fk = kinematics::forwardKinematics(nominal, nominal_data, r.readings, seed, options.fk);
  r.command = r.fk.ok() ? nominal_data.pose : desired;
  return r;
}

}  // namespace

PredistortionResult predistort(const kinematics::HexapodModel& nominal,
                               const kinematics::HexapodModel& calibrated,
                               const kinematics::PoseRpy& desired,
                               const kinematics::PoseRpy& seed,
                               const PredistortionOptions& options) {
  checkModels(nominal, calibrated, options);
  kinematics::HexapodData nd(nominal), cd(calibrated);
  return solve(nominal, calibrated, nd, cd, desired, seed, options);
}

PredistortionResult predistort(const kinematics::HexapodModel& nominal,
                               const kinematics::HexapodModel& calibrated,
                               const kinematics::PoseRpy& desired,
                               const PredistortionOptions& options) {
  return predistort(nominal, calibrated, desired, desired, options);
}

std::vector<PredistortionResult> predistortPath(const kinematics::HexapodModel& nominal,
                                                const kinematics::HexapodModel& calibrated,
                                                std::span<const kinematics::PoseRpy> desired,
                                                const PredistortionOptions& options) {
  checkModels(nominal, calibrated, options);
  kinematics::HexapodData nd(nominal), cd(calibrated);
  std::vector<PredistortionResult> out;
  out.reserve(desired.size());
  for (std::size_t k = 0; k < desired.size(); ++k) {
    kinematics::PoseRpy seed = desired[k];
    if (k > 0 && out.back().ok()) {
      seed.position += out.back().command.position - desired[k - 1].position;
      seed.rpy += out.back().command.rpy - desired[k - 1].rpy;
    }
    out.push_back(solve(nominal, calibrated, nd, cd, desired[k], seed, options));
  }
  return out;
}

}  // namespace pkm::compensation
