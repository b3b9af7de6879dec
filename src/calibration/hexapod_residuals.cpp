#include "detail/hexapod_residuals.hpp"

#include <algorithm>
#include <cmath>

#include "detail/observations.hpp"
#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/core/error.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"

namespace pkm::calibration {
namespace {

using detail::FrameEstimate;
using detail::ObservationRef;
using kinematics::HexapodData;
using kinematics::HexapodModel;

}  // namespace

void detail::stackHexapodObservations(const HexapodModel& model,
                                      const HexapodCalibrationData& data,
                                      const FrameEstimate* frame,
                                      Eigen::MatrixXd* J,
                                      Eigen::VectorXd* r,
                                      ResidualStatistics* stats,
                                      const kinematics::StrutVector* backlash) {
  const auto refs = detail::observations(data);
  const auto rows = static_cast<Eigen::Index>(data.equations());
  const Eigen::Index n_frame = frame != nullptr ? 6 : 0;
  const Eigen::Index cols = kHexapodParameters + n_frame + (backlash != nullptr ? 6 : 0);
  if (J != nullptr) J->setZero(rows, cols);
  if (r != nullptr) r->setZero(rows);
  HexapodData work(model);
  Eigen::Index row = 0;
  double sum = 0.0;
  for (const ObservationRef& ref : refs) {
    const Eigen::Index n = ref.rows();
    double res[6];
    Eigen::MatrixXd Jt, Jf, Jb;
    const bool ok = detail::evaluate(model,
                                     work,
                                     data,
                                     ref,
                                     frame,
                                     res,
                                     J != nullptr ? &Jt : nullptr,
                                     J != nullptr && frame != nullptr ? &Jf : nullptr,
                                     backlash,
                                     J != nullptr && backlash != nullptr ? &Jb : nullptr);
    if (ok) {
      if (J != nullptr) {
        J->block(row, 0, n, kHexapodParameters) = Jt;
        if (frame != nullptr) J->block(row, kHexapodParameters, n, 6) = Jf;
        if (backlash != nullptr) J->block(row, kHexapodParameters + n_frame, n, 6) = Jb;
      }
      for (Eigen::Index k = 0; k < n; ++k) {
        if (r != nullptr) (*r)(row + k) = res[k];
        if (stats != nullptr) {
          sum += res[k] * res[k];
          stats->max = std::max(stats->max, std::fabs(res[k]));
          ++stats->equations;
        }
      }
    } else if (stats != nullptr) {
      ++stats->fk_failures;
    }
    row += n;
  }
  if (stats != nullptr) stats->rms = stats->equations > 0 ? std::sqrt(sum / stats->equations) : 0.0;
}

void detail::requireFiniteHexapodData(const HexapodCalibrationData& data) {
  for (std::size_t k = 0; k < data.poses.size(); ++k) {
    const PoseObservation& o = data.poses[k];
    PKM_CHECK(o.readings.allFinite() && o.pose.position.allFinite() && o.pose.rpy.allFinite(),
              "calibration: pose observation {} has a non-finite value",
              k + 1);
  }
  for (std::size_t k = 0; k < data.points.size(); ++k) {
    const PointObservation& o = data.points[k];
    PKM_CHECK(o.readings.allFinite() && o.point.allFinite(),
              "calibration: point observation {} has a non-finite value",
              k + 1);
  }
  const auto finite_station = [](const GaugeStation& st) {
    return st.readings.allFinite() && st.command.position.allFinite() &&
           st.command.rpy.allFinite() && std::isfinite(st.gauges[0]) &&
           std::isfinite(st.gauges[1]) && std::isfinite(st.gauges[2]);
  };
  for (std::size_t k = 0; k < data.distances.size(); ++k) {
    const DistanceObservation& o = data.distances[k];
    PKM_CHECK(o.readings.allFinite() && o.from_point.allFinite() && std::isfinite(o.distance) &&
                  o.distance >= 0.0 && (!o.readings_from || o.readings_from->allFinite()),
              "calibration: distance observation {} has a non-finite or negative value",
              k + 1);
  }
  for (std::size_t k = 0; k < data.constrained.size(); ++k) {
    const ConstrainedMotionData& c = data.constrained[k];
    PKM_CHECK(std::fabs(c.table_normal.norm() - 1.0) < 1e-9,
              "calibration: constrained set {}: the table normal is not a unit vector",
              k + 1);
    PKM_CHECK(finite_station(c.reference),
              "calibration: constrained set {}: the reference has a non-finite value",
              k + 1);
    for (std::size_t j = 0; j < c.stations.size(); ++j)
      PKM_CHECK(finite_station(c.stations[j]),
                "calibration: constrained set {}: station {} has a non-finite value",
                k + 1,
                j + 1);
  }
}

std::size_t HexapodCalibrationData::equations() const {
  std::size_t n = 6 * poses.size() + 3 * points.size() + distances.size();
  for (const ConstrainedMotionData& c : constrained) n += 3 * c.stations.size();
  return n;
}

const std::vector<std::string>& measurementFrameNames() {
  static const std::vector<std::string> names{
      "frame.x", "frame.y", "frame.z", "frame.rx", "frame.ry", "frame.rz"};
  return names;
}

geometry::RigidTransform initialMeasurementFrame(const HexapodModel& model,
                                                 const HexapodCalibrationData& data) {
  std::vector<Eigen::Vector3d> world, measured;
  HexapodData work(model);
  const auto add = [&](const kinematics::StrutVector& q, const Eigen::Vector3d& p) {
    if (kinematics::forwardKinematics(model, work, q, model.home).ok()) {
      world.push_back(work.world_p_tcp);
      measured.push_back(p);
    }
  };
  for (const PoseObservation& o : data.poses) add(o.readings, o.pose.position);
  for (const PointObservation& o : data.points) add(o.readings, o.point);
  PKM_CHECK(world.size() >= 3,
            "calibration: only {} observations have a converging FK; the measurement frame needs 3",
            world.size());
  return geometry::fitRigidTransform(world, measured);
}

Eigen::MatrixXd identificationJacobian(const HexapodModel& model,
                                       const HexapodCalibrationData& data) {
  Eigen::MatrixXd J;
  FrameEstimate frame;
  if (data.measurement_frame) frame.initial = *data.measurement_frame;
  detail::stackHexapodObservations(
      model, data, data.measurement_frame ? &frame : nullptr, &J, nullptr, nullptr);
  return J;
}

ResidualStatistics residualStatistics(const HexapodModel& model,
                                      const HexapodCalibrationData& data,
                                      const std::optional<geometry::RigidTransform>& frame,
                                      const std::optional<kinematics::StrutVector>& backlash) {
  ResidualStatistics s;
  const std::optional<geometry::RigidTransform>& f = frame ? frame : data.measurement_frame;
  FrameEstimate estimate;
  if (f) estimate.initial = *f;
  detail::stackHexapodObservations(
      model, data, f ? &estimate : nullptr, nullptr, nullptr, &s, backlash ? &*backlash : nullptr);
  return s;
}

const std::vector<std::string>& backlashNames() {
  static const std::vector<std::string> names{
      "backlash0", "backlash1", "backlash2", "backlash3", "backlash4", "backlash5"};
  return names;
}

std::vector<kinematics::StrutVector> approachFromSequence(
    const std::vector<kinematics::StrutVector>& readings, double first) {
  std::vector<kinematics::StrutVector> out;
  kinematics::StrutVector d = kinematics::StrutVector::Constant(first);
  for (std::size_t k = 0; k < readings.size(); ++k) {
    if (k > 0)
      for (int i = 0; i < kinematics::kStruts; ++i) {
        const double change = readings[k](i) - readings[k - 1](i);
        if (change != 0.0) d(i) = change > 0.0 ? 1.0 : -1.0;
      }
    out.push_back(d);
  }
  return out;
}

std::vector<double> observationResidualNorms(
    const HexapodModel& model,
    const HexapodCalibrationData& data,
    const std::optional<geometry::RigidTransform>& frame,
    const std::optional<kinematics::StrutVector>& backlash) {
  const std::optional<geometry::RigidTransform>& f = frame ? frame : data.measurement_frame;
  FrameEstimate estimate;
  if (f) estimate.initial = *f;
  HexapodData work(model);
  std::vector<double> out;
  for (const ObservationRef& ref : detail::observations(data)) {
    double r[6];
    const bool ok = detail::evaluate(model,
                                     work,
                                     data,
                                     ref,
                                     f ? &estimate : nullptr,
                                     r,
                                     nullptr,
                                     nullptr,
                                     backlash ? &*backlash : nullptr,
                                     nullptr);
    out.push_back(ok ? Eigen::Map<const Eigen::VectorXd>(r, ref.rows()).norm() : -1.0);
  }
  return out;
}

}  // namespace pkm::calibration
