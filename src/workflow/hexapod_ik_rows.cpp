// Hexapod IK of many poses on the cores (workflow/hexapod_ik_rows.hpp).
#include "pkm/workflow/hexapod_ik_rows.hpp"

#include <cassert>

#include "pkm/core/parallel.hpp"
#include "pkm/core/units.hpp"
#include "pkm/kinematics/hexapod_checks.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::workflow {

namespace {

kinematics::PoseRpy poseOfRow(const double* p) {
  kinematics::PoseRpy pose;
  pose.position = {p[0], p[1], p[2]};
  pose.rpy = {degToRad(p[3]), degToRad(p[4]), degToRad(p[5])};
  return pose;
}

}  // namespace

void hexapodIkRows(const kinematics::HexapodModel& model,
                   std::span<const double> poses,
                   std::span<double> readings,
                   std::span<std::string_view> status) {
  assert(poses.size() % 6 == 0 && readings.size() == poses.size());
  const std::size_t rows = poses.size() / 6;
  assert(status.empty() || status.size() == rows);
  // Rows per chunk: an IK costs about 0.1 µs, so a thread pays off from some ten thousand rows.
  forEachChunk(rows, kParallelChunks, [&](std::size_t, std::size_t begin, std::size_t end) {
    kinematics::HexapodData data(model);
    for (std::size_t i = begin; i < end; ++i) {
      const kinematics::PoseRpy pose = poseOfRow(poses.data() + 6 * i);
      Eigen::Map<kinematics::StrutVector> out(readings.data() + 6 * i);
      if (status.empty()) {
        out = kinematics::inverseKinematics(model, data, pose);
      } else {
        const kinematics::HexapodCheckResult c = kinematics::checkPose(model, data, pose);
        out = c.readings;
        status[i] = c.status();
      }
    }
  });
}

}  // namespace pkm::workflow
