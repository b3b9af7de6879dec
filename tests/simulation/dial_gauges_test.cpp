// Constrained motion with three dial gauges (seed 004): exact nominal lengths without errors; with
// assembly errors the platform is driven back onto the gauges' plane and the recorded lengths
// carry the errors; the operator on any rig approaches every command from below.
#include "pkm/simulation/dial_gauges.hpp"

#include <gtest/gtest.h>

#include "pkm/core/error.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace kin = pkm::kinematics;
namespace sim = pkm::simulation;

sim::DialGaugeSetup setup() {
  sim::DialGaugeSetup s;
  s.reference = Eigen::VectorXd::Zero(6);
  s.reference[2] = 200;
  s.stations = {{100, 0, 0}, {0, -80, 0}, {-60, 70, 0.1}, {50, 50, -0.15}};
  return s;
}

TEST(DialGauges, WithoutErrorsTheNominalLengthsAreRecorded) {
  sim::HexapodVirtualMachine m(pkm::test::millingModel(), {});
  sim::RandomStream rng(1);
  const sim::DialGaugeSetup s = setup();
  const auto stations = sim::simulateDialGauges(m, s, rng);
  ASSERT_EQ(stations.size(), 5U);
  kin::HexapodData data(m.nominal());
  for (std::size_t j = 1; j < stations.size(); ++j) {
    EXPECT_EQ(stations[j].iterations, 1);
    EXPECT_TRUE(stations[j].converged);
    const Eigen::VectorXd& c = stations[j].command;
    EXPECT_EQ(c[2], 200.0);
    EXPECT_EQ(c[5], s.stations[j - 1][2]);
    kin::PoseRpy pose;
    pose.position = c.head<3>();
    pose.rpy = c.tail<3>();
    EXPECT_TRUE(stations[j].lengths == kin::inverseKinematics(m.nominal(), data, pose));
  }
}

TEST(DialGauges, AssemblyErrorsAreDrivenOutAndShowInTheLengths) {
  sim::HexapodAssemblyErrors e;
  for (int i = 0; i < kin::kStruts; ++i) {
    const auto iu = static_cast<std::size_t>(i);
    e.base_joint[iu] = Eigen::Vector3d(0.3 * (i - 2.5), -0.2 * (i % 3), 0.4);
    e.platform_joint[iu] = Eigen::Vector3d(-0.1 * i, 0.25, -0.15 * (i % 2));
    e.length_offset[i] = 0.5 - 0.2 * i;
  }
  sim::HexapodVirtualMachine m(pkm::test::millingModel(), e);
  sim::RandomStream rng(1);
  sim::DialGaugeSetup s = setup();
  s.noise = {0.0, 0.0, 1e-3};  // a 1 µm dial gauge
  const auto stations = sim::simulateDialGauges(m, s, rng);
  double largest_correction = 0.0;
  for (std::size_t j = 1; j < stations.size(); ++j) {
    EXPECT_TRUE(stations[j].converged) << j;
    EXPECT_GT(stations[j].iterations, 1);
    for (const double r : stations[j].readings) EXPECT_LE(std::abs(r), s.tolerance);
    largest_correction = std::max(largest_correction, std::abs(stations[j].command[2] - 200.0));
  }
  // The operator had to change z by far more than the gauges' tolerance: the errors are in the
  // data.
  EXPECT_GT(largest_correction, 10 * s.tolerance);
  sim::RandomStream again(1);
  EXPECT_TRUE(sim::simulateDialGauges(m, s, again).back().lengths == stations.back().lengths);
}

/// A rig that records what the operator does and whose gauges read a fixed height error that
/// the operator's first correction removes.
class RecordingRig final : public sim::ConstrainedMotionRig {
 public:
  std::vector<std::string> events;
  kin::StrutVector moveTo(const Eigen::VectorXd& c) override {
    events.push_back("move z=" + std::to_string(c[2]));
    last_z_ = c[2];
    return kin::StrutVector::Constant(c[2]);
  }
  void zeroGauges() override { events.push_back("zero"); }
  Eigen::Vector3d readGauges() override {
    events.push_back("read");
    const bool corrected = last_z_ != 200.0;
    return Eigen::Vector3d::Constant(corrected ? 0.0 : 0.5);  // 0.5 mm high until corrected
  }

 private:
  double last_z_ = 0;
};

TEST(DialGauges, EveryMoveApproachesFromBelowAndTheOperatorReportsEachStation) {
  sim::DialGaugeSetup s = setup();
  s.stations.resize(1);
  s.approach = 1.0;
  RecordingRig rig;
  std::vector<int> reported;
  const auto out = sim::runConstrainedMotion(
      rig, s, [&](const sim::DialGaugeStation& st) { reported.push_back(st.station); });
  ASSERT_EQ(out.size(), 2U);
  EXPECT_EQ(reported, (std::vector<int>{0, 1}));
  const std::vector<std::string> want = {"move z=199.000000",
                                         "move z=200.000000",
                                         "zero",  // the reference
                                         "move z=199.000000",
                                         "move z=200.000000",
                                         "read",  // station 1: 0.5 mm high
                                         "move z=198.500000",
                                         "move z=199.500000",
                                         "read"};  // corrected, from below
  EXPECT_EQ(rig.events, want);
  EXPECT_EQ(out[1].iterations, 2);
  EXPECT_TRUE(out[1].converged);
  EXPECT_NEAR(out[1].command[2], 199.5, 1e-6);
  EXPECT_EQ(out[1].lengths[0], out[1].command[2]);  // the last move's commanded readings
}

TEST(DialGauges, InvalidSetupsThrow) {
  sim::DialGaugeSetup s = setup();
  s.gauge_points[2] = 2 * s.gauge_points[1] - s.gauge_points[0];
  EXPECT_THROW(s.validate(), pkm::InvalidArgument);
  s = setup();
  s.reference = Eigen::VectorXd::Zero(3);
  EXPECT_THROW(s.validate(), pkm::InvalidArgument);
  s = setup();
  s.tolerance = 0;
  EXPECT_THROW(s.validate(), pkm::InvalidArgument);
  s = setup();
  s.approach = -1;
  EXPECT_THROW(s.validate(), pkm::InvalidArgument);
}

}  // namespace PKM_TEST_NS
