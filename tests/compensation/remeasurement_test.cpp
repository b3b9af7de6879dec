// Proof by re-measurement (docs/compensation.md, "Verification"): a simulated Cartesian X axis with
// a known positioning error, backlash and repeatability is measured with the ISO 230-2 cycle, the
// table is written in a controller format, parsed back, applied with the controller's semantics to
// the axis commands, and the axis is measured again with other targets and noise.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <utility>

#include "pkm/compensation/axis_table.hpp"
#include "pkm/compensation/linuxcnc_comp.hpp"
#include "pkm/compensation/siemens_comp.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/metrology/iso230_2.hpp"
#include "pkm/simulation/cartesian_machine.hpp"
#include "pkm/simulation/line_measurement.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace comp = pkm::compensation;
namespace sim = pkm::simulation;
namespace met = pkm::metrology;

constexpr double kTravel = 500.0;         // mm
constexpr double kSlope = 20e-6;          // linear positioning error, mm/mm (20 µm/m)
constexpr double kWave = 5e-3;            // periodic error amplitude, mm
constexpr double kPeriod = 400.0;         // its period, mm
constexpr double kBacklash = 8e-3;        // lost motion b, mm
constexpr double kSigma = 0.5e-3;         // repeatability σ per move, mm
constexpr double kRequiredDrop = 0.9;     // E must drop by at least 90 %
constexpr double kSigmaMultiple = 6.0;    // ... and end within this many σ
constexpr double kWrongSignGrowth = 1.5;  // a wrong sign must make M at least this much larger

/// EXX(x) = slope·x + wave·sin(2πx/period), tabulated every 2.5 mm (held outside).
pkm::geometry::ErrorTable1d positioningError() {
  std::vector<double> x;
  Eigen::MatrixXd v = Eigen::MatrixXd::Zero(201, 6);
  for (int i = 0; i <= 200; ++i) {
    x.push_back(2.5 * i);
    v(i, 0) = kSlope * x.back() + kWave * std::sin(2.0 * std::numbers::pi * x.back() / kPeriod);
  }
  return {x, v};
}

sim::CartesianMachine axisX() {
  sim::CartesianErrors errors;
  errors.axes[0] = positioningError();
  sim::CartesianActuation act;
  act.backlash = {kBacklash, 0.0, 0.0};
  act.repeatability_sigma = {kSigma, 0.0, 0.0};
  return sim::CartesianMachine({}, errors, act);
}

/// A controller between the program and the X drive: the commanded x becomes
/// `drive(x, direction)`, the direction being the sign of the last change of the command (kept
/// while it does not change; + after reset, as the machine).
class ControlledAxis final : public sim::VirtualMachine {
 public:
  ControlledAxis(sim::VirtualMachine& drive, std::function<double(double, int)> law)
      : drive_(drive), law_(std::move(law)) {}
  [[nodiscard]] std::vector<std::string> axisNames() const override { return drive_.axisNames(); }
  [[nodiscard]] pkm::geometry::RigidTransform nominalPose(
      const Eigen::VectorXd& command) const override {
    return drive_.nominalPose(command);
  }
  pkm::geometry::RigidTransform moveTo(const Eigen::VectorXd& command) override {
    const double x = command[0];
    if (moved_ && x != last_) direction_ = x > last_ ? 1 : -1;
    last_ = x;
    moved_ = true;
    Eigen::VectorXd motor = command;
    motor[0] = law_(x, direction_);
    return drive_.moveTo(motor);
  }
  void reset(std::uint64_t seed) override {
    drive_.reset(seed);
    moved_ = false;
    direction_ = 1;
  }

 private:
  sim::VirtualMachine& drive_;
  std::function<double(double, int)> law_;
  double last_ = 0.0;
  int direction_ = 1;
  bool moved_ = false;
};

/// ISO 230-2 of a laser positioning run along X (21 jittered targets, 5 bidirectional runs).
met::Iso230_2Result measure(sim::VirtualMachine& m, std::uint64_t seed) {
  sim::LineSetup s;
  s.name = "linear-x";
  s.line.start = Eigen::Vector3d(0, 0, 0);
  s.line.direction = Eigen::Vector3d(1, 0, 0);
  s.cycle = {.first = 0.0,
             .last = kTravel,
             .targets = 21,
             .target_jitter = 6.0,
             .runs = 5,
             .overshoot = 5.0,
             .bidirectional = true};
  sim::RandomStream rng(seed);
  std::vector<met::PositioningSample> samples;
  for (const sim::LineRun& run : sim::simulateLine(m, s, rng)) {
    for (const sim::LineReading& r : run.readings) {
      samples.push_back({r.target, r.direction, run.run, r.reading});
    }
  }
  return met::evaluateIso230_2(samples);
}

TEST(Remeasurement, LinuxcncType1TableRemovesSystematicDeviation) {
  sim::CartesianMachine machine = axisX();
  const met::Iso230_2Result before = measure(machine, pkm::test::kSeed);
  ASSERT_TRUE(before.bidirectional);
  // The injected reversal is seen: B_i = −b.
  EXPECT_NEAR(before.B_mean, -kBacklash, 3 * kSigma);

  const comp::AxisErrorTable table = comp::tableFromIso230_2(before, "X");
  const std::string text = comp::writeLinuxcncComp(comp::linuxcncCompFromTable(table, 1));
  const comp::LinuxcncCompFile file = comp::parseLinuxcncComp(text, "xcomp.txt", 1);

  ControlledAxis controlled(
      machine, [&file](double x, int dir) { return comp::applyLinuxcncComp(file, x, dir); });
  const met::Iso230_2Result after = measure(controlled, pkm::test::kSeed + 1);
  RecordProperty("E_before_mm", std::to_string(before.E));
  RecordProperty("E_after_mm", std::to_string(after.E));
  EXPECT_LE(after.E, (1.0 - kRequiredDrop) * before.E) << "E before " << before.E;
  EXPECT_LE(after.E, kSigmaMultiple * kSigma) << "E after " << after.E;
  EXPECT_LE(std::abs(after.B_mean), 3 * kSigma);  // the backlash is compensated too
}

TEST(Remeasurement, LinuxcncType0TableGivesTheSameMotorCommands) {
  sim::CartesianMachine machine = axisX();
  const comp::AxisErrorTable table =
      comp::tableFromIso230_2(measure(machine, pkm::test::kSeed), "X");
  const auto f0 = comp::parseLinuxcncComp(
      comp::writeLinuxcncComp(comp::linuxcncCompFromTable(table, 0)), "t0", 0);
  const auto f1 = comp::parseLinuxcncComp(
      comp::writeLinuxcncComp(comp::linuxcncCompFromTable(table, 1)), "t1", 1);
  for (double x = -10.0; x <= kTravel + 10.0; x += 0.37) {
    for (int dir : {1, -1}) {
      // type 0 stores P + e, LinuxCNC's trim is P − (P + e): equal up to the rounding of P + e.
      EXPECT_NEAR(comp::applyLinuxcncComp(f0, x, dir),
                  comp::applyLinuxcncComp(f1, x, dir),
                  pkm::test::kTolRoundTrip);
    }
  }
}

TEST(Remeasurement, SiemensEecTableRemovesMeanDeviationWithTheK3Sign) {
  sim::CartesianMachine machine = axisX();
  const met::Iso230_2Result before = measure(machine, pkm::test::kSeed);
  const comp::FormatTraits eec = comp::traits(comp::TableFormat::kSiemensEec);
  const comp::AxisErrorTable table =
      comp::fitToTarget(comp::tableFromIso230_2(before, "X1"), eec, eec.default_max_points);
  const comp::SiemensEecTable parsed =
      comp::parseSiemensEec(comp::writeSiemensEec(comp::siemensEecFromTable(table)), "eec.mpf");

  // K3: a positive value moves the axis in −.
  ControlledAxis controlled(machine, [&parsed](double x, int) { return parsed.axisCommand(x); });
  const met::Iso230_2Result after = measure(controlled, pkm::test::kSeed + 1);
  RecordProperty("M_before_mm", std::to_string(before.M));
  RecordProperty("M_after_mm", std::to_string(after.M));
  EXPECT_LE(after.M, (1.0 - kRequiredDrop) * before.M) << "M before " << before.M;
  EXPECT_LE(after.M, kSigmaMultiple * kSigma) << "M after " << after.M;
  // EEC has no direction: the reversal stays (for MD32450 backlash compensation).
  EXPECT_NEAR(after.B_mean, before.B_mean, 3 * kSigma);

  // The opposite sign doubles the error instead.
  ControlledAxis wrong(machine, [&parsed](double x, int) { return x + parsed.valueAt(x); });
  const met::Iso230_2Result worse = measure(wrong, pkm::test::kSeed + 1);
  EXPECT_GE(worse.M, kWrongSignGrowth * before.M);
}

}  // namespace PKM_TEST_NS
