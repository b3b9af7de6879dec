// live::planGaugeStations: the stations an automated constrained-motion calibration drives to are
// moves the machine can make (checked as `pkm hexapod check` checks), reached from below with every
// strut moving the same way, chosen by the pose planner better than at random, and held-out ones
// apart.
#include "pkm/live/gauge_stations.hpp"

#include <gtest/gtest.h>

#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "pkm/workflow/pose_checks.hpp"

namespace pkm::live {
namespace PKM_TEST_NS {

simulation::DialGaugeSetup setupAt(const Eigen::VectorXd& reference) {
  simulation::DialGaugeSetup s;
  s.reference = reference;
  s.approach = 1.0;
  return s;
}

GaugeStationOptions wide() {
  GaugeStationOptions o;
  o.axis_min.fill(-1e9);
  o.axis_max.fill(1e9);
  return o;
}

TEST(GaugeStations, ArePlannedWithinWhatTheMachineCanDo) {
  const io::HexapodMachine m = io::loadHexapodMachine("hexapod-default");
  Eigen::VectorXd ref(6);
  ref << 0, 0, 200, 0, 0, 0;
  const simulation::DialGaugeSetup setup = setupAt(ref);
  const GaugeStationPlan plan = planGaugeStations(m, setup, wide());
  ASSERT_EQ(plan.fit.size(), 36u);
  ASSERT_EQ(plan.holdout.size(), 4u);
  EXPECT_GT(plan.candidates, 28);
  EXPECT_GT(plan.index_value, plan.random_baseline);
  EXPECT_GE(plan.identifiable, 20);
  EXPECT_LT(plan.identifiable, 42);  // plane contacts cannot see every parameter
  kinematics::HexapodData data(m.model);
  std::vector<Eigen::Vector3d> all = plan.fit;
  all.insert(all.end(), plan.holdout.begin(), plan.holdout.end());
  for (std::size_t i = 0; i < all.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) EXPECT_NE(all[i], all[j]) << i << " " << j;
    const std::array<double, 6> pose{all[i][0], all[i][1], 200, 0, 0, radToDeg(all[i][2])};
    EXPECT_EQ(workflow::checkHexapodPose(m.model, data, pose).status, "ok");
    const kinematics::StrutVector at =
        kinematics::inverseKinematics(m.model, data, {{pose[0], pose[1], 200}, {0, 0, all[i][2]}});
    const kinematics::StrutVector below =
        kinematics::inverseKinematics(m.model, data, {{pose[0], pose[1], 199}, {0, 0, all[i][2]}});
    EXPECT_TRUE(((at - below).array() < 0).all()) << i;  // this machine's struts hang down
  }
  std::printf("candidates %d of %d, identifiable %d, O1 %.3g (random %.3g)\n",
              plan.candidates,
              plan.tried,
              plan.identifiable,
              plan.index_value,
              plan.random_baseline);
}

TEST(GaugeStations, AxisLimitsAndTooFewCandidatesAreRespected) {
  const io::HexapodMachine m = io::loadHexapodMachine("hexapod-default");
  Eigen::VectorXd ref(6);
  ref << 0, 0, 200, 0, 0, 0;
  GaugeStationOptions o = wide();
  o.axis_min[0] = -50;  // LinuxCNC's [AXIS_X] MIN_LIMIT
  const GaugeStationPlan plan = planGaugeStations(m, setupAt(ref), o);
  for (const Eigen::Vector3d& s : plan.fit) EXPECT_GE(s[0], -50.0);
  o.count = 400;
  EXPECT_THROW((void)planGaugeStations(m, setupAt(ref), o), InvalidArgument);
  o = wide();
  o.axis_max[2] = 150;  // the reference itself is beyond a limit
  EXPECT_THROW((void)planGaugeStations(m, setupAt(ref), o), InvalidArgument);
  o = wide();
  o.grid = 4;
  EXPECT_THROW((void)planGaugeStations(m, setupAt(ref), o), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::live
