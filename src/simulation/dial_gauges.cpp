#include "pkm/simulation/dial_gauges.hpp"

#include <Eigen/LU>
#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"

namespace pkm::simulation {

namespace {

constexpr Eigen::Index kZ = 2;     // command index of z
constexpr double kStepMm = 1e-3;   // central-difference step for z, mm
constexpr double kStepRad = 1e-6;  // and for a, b, rad

/// The heights of the three tips along the normal for `pose`.
Eigen::Vector3d heights(const DialGaugeSetup& s, const geometry::RigidTransform& pose) {
  Eigen::Vector3d h;
  for (Eigen::Index k = 0; k < 3; ++k)
    h[k] = s.table_normal.normalized().dot(pose * s.gauge_points[static_cast<std::size_t>(k)]);
  return h;
}

}  // namespace

void DialGaugeSetup::validate() const {
  PKM_CHECK(reference.size() == 6 && reference.allFinite(),
            "{}: the reference must be 6 finite values",
            name);
  const Eigen::Vector3d area =
      (gauge_points[1] - gauge_points[0]).cross(gauge_points[2] - gauge_points[0]);
  PKM_CHECK(area.norm() > 1e-6, "{}: the three gauges are collinear", name);
  PKM_CHECK(table_normal.allFinite() && table_normal.norm() > 1e-12,
            "{}: the table normal is zero",
            name);
  PKM_CHECK(tolerance > 0.0, "{}: the tolerance must be > 0", name);
  PKM_CHECK(max_iterations >= 1, "{}: max_iterations must be >= 1", name);
  for (const Eigen::Vector3d& st : stations)
    PKM_CHECK(st.allFinite(), "{}: a station is not finite", name);
  noise.validate();
}

std::vector<DialGaugeStation> simulateDialGauges(HexapodVirtualMachine& machine,
                                                 const DialGaugeSetup& setup,
                                                 RandomStream& rng) {
  setup.validate();
  machine.reset(rng.bits());
  const Eigen::Vector3d zero = heights(setup, machine.moveTo(setup.reference));
  std::vector<DialGaugeStation> out;
  DialGaugeStation ref;
  ref.command = setup.reference;
  ref.lengths = machine.commandedReadings();
  ref.iterations = 1;
  ref.converged = true;
  out.push_back(ref);
  for (std::size_t j = 0; j < setup.stations.size(); ++j) {
    DialGaugeStation st;
    st.station = static_cast<int>(j) + 1;
    st.command = setup.reference;
    st.command[0] += setup.stations[j][0];
    st.command[1] += setup.stations[j][1];
    st.command[5] += setup.stations[j][2];
    while (true) {
      const Eigen::Vector3d truth = heights(setup, machine.moveTo(st.command)) - zero;
      Eigen::Vector3d r;
      for (Eigen::Index k = 0; k < 3; ++k) r[k] = setup.noise.apply(truth[k], 0.0, rng);
      ++st.iterations;
      st.readings = {r[0], r[1], r[2]};
      st.lengths = machine.commandedReadings();
      st.converged = r.cwiseAbs().maxCoeff() <= setup.tolerance;
      if (st.converged || st.iterations >= setup.max_iterations) break;
      // Sensitivity of the heights to (z, a, b) on the nominal model, central differences.
      Eigen::Matrix3d S;
      for (Eigen::Index c = 0; c < 3; ++c) {
        const double h = c == 0 ? kStepMm : kStepRad;
        Eigen::VectorXd plus = st.command, minus = st.command;
        plus[kZ + c] += h;
        minus[kZ + c] -= h;
        S.col(c) = (heights(setup, machine.nominalPose(plus)) -
                    heights(setup, machine.nominalPose(minus))) /
                   (2 * h);
      }
      st.command.segment<3>(kZ) -= S.partialPivLu().solve(r);
    }
    out.push_back(st);
  }
  return out;
}

}  // namespace pkm::simulation
