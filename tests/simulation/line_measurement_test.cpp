// Line measurements: the ISO 230-2 cycle, nominal readings without errors or noise, each injected
// error with its analytic first-order size (positioning, straightness, misalignment, squareness in
// face and body diagonals, Abbe offset, angular), and the spread of the instrument noise.
#include "pkm/simulation/line_measurement.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/simulation/cartesian_machine.hpp"
#include "pkm/simulation/hybrid_virtual_machine.hpp"
#include "support/hybrid_samples.hpp"
#include "support/statistics.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace sim = pkm::simulation;
using pkm::geometry::ErrorTable1d;
using pkm::test::kTolExact;

constexpr double kSlope = 20e-6;   // a positioning slope (20 ppm) or an angle per mm, rad/mm
constexpr double kAngle = 50e-6;   // rad
constexpr double kTravel = 500.0;  // mm
const double kTolFirstOrder = 10 * kAngle * kAngle * kTravel;

/// A table over [0, kTravel] whose `component` grows linearly from 0 to `end`.
ErrorTable1d ramp(int component, double end) {
  Eigen::MatrixXd v = Eigen::MatrixXd::Zero(2, 6);
  v(1, component) = end;
  return ErrorTable1d({0.0, kTravel}, v);
}

sim::LineSetup lineSetup(sim::LineQuantity q,
                         const Eigen::Vector3d& from,
                         const Eigen::Vector3d& to) {
  sim::LineSetup s;
  s.name = "line";
  s.quantity = q;
  const double length = (to - from).norm();
  s.line.start = from;
  s.line.direction = (to - from) / length;
  s.cycle.first = 0.0;
  s.cycle.last = length;
  s.cycle.targets = 6;
  s.cycle.runs = 2;
  s.cycle.overshoot = 1.0;
  return s;
}

std::vector<sim::LineRun> measure(sim::VirtualMachine& m,
                                  const sim::LineSetup& s,
                                  std::uint64_t seed = 1) {
  sim::RandomStream rng(seed);
  return sim::simulateLine(m, s, rng);
}

TEST(LineMeasurement, CycleOrderAndNominalReadingsAreExact) {
  sim::CartesianMachine m({}, {});
  for (const auto q : {sim::LineQuantity::kLinear,
                       sim::LineQuantity::kStraightness,
                       sim::LineQuantity::kAngular}) {
    sim::LineSetup s = lineSetup(q, {0, 100, 50}, {kTravel, 100, 50});
    const auto runs = measure(m, s);
    ASSERT_EQ(runs.size(), 2U);
    for (const sim::LineRun& run : runs) {
      ASSERT_EQ(run.readings.size(), 12U);
      for (std::size_t i = 0; i < run.readings.size(); ++i) {
        const sim::LineReading& r = run.readings[i];
        EXPECT_EQ(r.direction, i < 6 ? 1 : -1);
        EXPECT_EQ(r.target, 100.0 * static_cast<double>(i < 6 ? i : 11 - i));
        EXPECT_EQ(r.reading, q == sim::LineQuantity::kLinear ? r.target : 0.0) << toString(q);
      }
    }
    EXPECT_EQ(runs[1].run, 2);
  }
}

TEST(LineMeasurement, PositioningErrorAppearsAsTheDeviation) {
  sim::CartesianErrors e;
  e.axes[0] = ramp(pkm::geometry::kDx, kSlope * kTravel);  // EXX = 20 ppm
  sim::CartesianMachine m({}, e);
  for (const auto& run :
       measure(m, lineSetup(sim::LineQuantity::kLinear, {0, 0, 0}, {kTravel, 0, 0})))
    for (const auto& r : run.readings)
      EXPECT_NEAR(r.reading - r.target, kSlope * r.target, kTolExact);
}

TEST(LineMeasurement, StraightnessAndBeamMisalignment) {
  sim::CartesianErrors e;
  Eigen::MatrixXd v = Eigen::MatrixXd::Zero(3, 6);
  v(1, pkm::geometry::kDy) = 0.003;  // EYX: 3 µm bow at mid-travel
  e.axes[0] = ErrorTable1d({0.0, kTravel / 2, kTravel}, v);
  sim::CartesianMachine m({}, e);
  sim::LineSetup s = lineSetup(sim::LineQuantity::kStraightness, {0, 0, 0}, {kTravel, 0, 0});
  s.lateral = Eigen::Vector3d::UnitY();
  for (const double misalignment : {0.0, kAngle}) {
    s.misalignment = misalignment;
    for (const auto& run : measure(m, s))
      for (const auto& r : run.readings) {
        const double bow = 0.003 * (1.0 - std::abs(r.target - kTravel / 2) / (kTravel / 2));
        EXPECT_NEAR(r.reading, bow + misalignment * r.target, kTolFirstOrder) << r.target;
      }
  }
}

TEST(LineMeasurement, SquarenessInFaceAndBodyDiagonals) {
  // First-order diagonal formula: deviation = −s·Σ sq_ij·u_i·u_j over the pairs of axes.
  sim::CartesianErrors e;
  e.squareness = {kAngle, -0.6 * kAngle, 0.4 * kAngle};
  sim::CartesianMachine m({}, e);
  const Eigen::Vector3d corner(kTravel, 400, 300);
  const Eigen::Vector3d face(kTravel, 400, 0);
  const struct {
    Eigen::Vector3d from, to;
  } lines[] = {{{0, 0, 150}, face + Eigen::Vector3d(0, 0, 150)},
               {{kTravel, 0, 150}, {0, 400, 150}},
               {{0, 0, 0}, corner},
               {{kTravel, 0, 0}, {0, 400, 300}},
               {{0, 400, 0}, {kTravel, 0, 300}},
               {{0, 0, 300}, {kTravel, 400, 0}}};
  for (const auto& l : lines) {
    const Eigen::Vector3d u = (l.to - l.from).normalized();
    const double per_mm = -(e.squareness.xy * u.x() * u.y() + e.squareness.xz * u.x() * u.z() +
                            e.squareness.yz * u.y() * u.z());
    for (const auto& run : measure(m, lineSetup(sim::LineQuantity::kLinear, l.from, l.to)))
      for (const auto& r : run.readings)
        EXPECT_NEAR(r.reading - r.target, per_mm * r.target, kTolFirstOrder) << u.transpose();
  }
}

TEST(LineMeasurement, AbbeOffsetTurnsPitchIntoPositioningError) {
  sim::CartesianErrors e;
  e.axes[0] = ramp(pkm::geometry::kEy, kSlope * kTravel);  // EBX grows to 10 mrad at 500 mm
  sim::CartesianMachine m({}, e);
  sim::LineSetup s = lineSetup(sim::LineQuantity::kLinear, {0, 0, 0}, {kTravel, 0, 0});
  const double h = 100.0;
  s.reflector_offset = {0, 0, h};
  for (const auto& run : measure(m, s))
    for (const auto& r : run.readings) {
      const double pitch = kSlope * r.target;
      EXPECT_NEAR(r.reading - r.target, h * std::sin(pitch), kTolExact * kTravel) << r.target;
    }
}

TEST(LineMeasurement, AngularReadsThePitch) {
  sim::CartesianErrors e;
  e.axes[0] = ramp(pkm::geometry::kEy, kSlope * kTravel);
  sim::CartesianMachine m({}, e);
  sim::LineSetup s = lineSetup(sim::LineQuantity::kAngular, {0, 0, 0}, {kTravel, 0, 0});
  s.lateral = Eigen::Vector3d::UnitY();
  for (const auto& run : measure(m, s))
    for (const auto& r : run.readings) EXPECT_NEAR(r.reading, kSlope * r.target, kTolExact);
}

TEST(LineMeasurement, Y2PositioningReadsEyyWithItsSign) {
  // Y2 moves the table: a positive EYY2 makes the axis travel further, deviation +EYY2.
  pkm::kinematics::GeometricErrors e;
  e.y2 = ramp(pkm::geometry::kDy, kSlope * kTravel);
  sim::HybridVirtualMachine m(pkm::test::mxt700sLikeModel(), e);
  sim::LineSetup s;
  s.name = "y2";
  s.line.start = Eigen::VectorXd::Zero(5);
  s.line.direction = Eigen::VectorXd::Unit(5, 1);
  s.cycle = {0.0, 350.0, 8, 0.0, 1, 0.0, true};
  for (const auto& run : measure(m, s))
    for (const auto& r : run.readings)
      EXPECT_NEAR(r.reading - r.target, kSlope * r.target, kTolExact);
}

TEST(LineMeasurement, StepDiagonalReadsAfterEachSingleAxisMove) {
  // Wang's step diagonal: during the X sub-move the reading changes by ux·ΔEXX (flat mirror).
  sim::CartesianErrors e;
  e.axes[0] = ramp(pkm::geometry::kDx, kSlope * kTravel);
  sim::CartesianMachine m({}, e);
  const Eigen::Vector3d corner(kTravel, 400, 300);
  sim::LineSetup s = lineSetup(sim::LineQuantity::kLinear, {0, 0, 0}, corner);
  s.procedure = sim::LineProcedure::kStepDiagonal;
  const Eigen::Vector3d u = corner.normalized();
  const auto runs = measure(m, s);
  ASSERT_EQ(runs[0].readings.size(), 2U * 6U * 3U);
  for (const auto& run : runs)
    for (std::size_t i = 0; i < run.readings.size(); ++i) {
      const sim::LineReading& r = run.readings[i];
      EXPECT_EQ(r.sub_step, static_cast<int>(i % 3) + 1);
      // X is at the step's target after its sub-move, and X moves first.
      const double x = u.x() * run.readings[i - i % 3 + 2].target;
      EXPECT_NEAR(r.reading - r.target, u.x() * kSlope * x, kTolExact) << i;
    }
  // The sub-step targets are the commanded points' nominal positions along the beam.
  const sim::LineReading& first_x = runs[0].readings[3];  // X moved to the second target
  EXPECT_NEAR(first_x.target, u.x() * u.x() * runs[0].readings[5].target, kTolExact);
  s.quantity = sim::LineQuantity::kStraightness;
  EXPECT_THROW(s.validate(), pkm::InvalidArgument);
  s = lineSetup(sim::LineQuantity::kLinear, {0, 0, 0}, {kTravel, 0, 0});
  s.procedure = sim::LineProcedure::kStepDiagonal;
  EXPECT_THROW(s.validate(), pkm::InvalidArgument);
}

TEST(LineMeasurement, NoiseHasTheSpecifiedSpread) {
  sim::CartesianMachine m({}, {});
  sim::LineSetup s = lineSetup(sim::LineQuantity::kLinear, {0, 0, 0}, {kTravel, 0, 0});
  s.cycle.runs = 400;
  s.noise.sigma = 1e-5;
  std::vector<double> dev;
  for (const auto& run : measure(m, s, pkm::test::kSeed))
    for (const auto& r : run.readings) dev.push_back(r.reading - r.target);
  EXPECT_NEAR(pkm::test::sampleMean(dev), 0.0, pkm::test::meanTolerance(dev.size(), s.noise.sigma));
  EXPECT_NEAR(
      pkm::test::sampleSigma(dev) / s.noise.sigma, 1.0, pkm::test::sigmaRatioTolerance(dev.size()));
}

TEST(LineMeasurement, RandomTargetsAreSharedByAllRunsAndKeepTheEnds) {
  sim::CartesianMachine m({}, {});
  sim::LineSetup s = lineSetup(sim::LineQuantity::kLinear, {0, 0, 0}, {kTravel, 0, 0});
  s.cycle.targets = 11;
  s.cycle.target_jitter = 5.0;
  const auto runs = measure(m, s, pkm::test::kSeed);
  const auto& first = runs[0].readings;
  EXPECT_EQ(first.front().target, 0.0);
  EXPECT_EQ(first[10].target, kTravel);
  bool moved = false;
  for (std::size_t i = 1; i < 10; ++i) {
    EXPECT_LE(std::abs(first[i].target - 50.0 * static_cast<double>(i)), 5.0);
    EXPECT_LT(first[i - 1].target, first[i].target);
    moved = moved || first[i].target != 50.0 * static_cast<double>(i);
    EXPECT_EQ(runs[1].readings[i].target, first[i].target);
  }
  EXPECT_TRUE(moved);
  const auto again = measure(m, s, pkm::test::kSeed);
  EXPECT_EQ(again[1].readings[3].target, runs[1].readings[3].target);
}

TEST(LineMeasurement, InvalidSetupsThrow) {
  sim::CartesianMachine m({}, {});
  sim::LineSetup s = lineSetup(sim::LineQuantity::kLinear, {0, 0, 0}, {kTravel, 0, 0});
  s.cycle.target_jitter = 50.0;  // half the spacing of 100 mm
  EXPECT_THROW((void)measure(m, s), pkm::InvalidArgument);
  s = lineSetup(sim::LineQuantity::kLinear, {0, 0, 0}, {kTravel, 0, 0});
  s.line.direction *= 2.0;  // 2 mm of tool travel per unit of s
  EXPECT_THROW((void)measure(m, s), pkm::InvalidArgument);
  s = lineSetup(sim::LineQuantity::kStraightness, {0, 0, 0}, {kTravel, 0, 0});
  s.lateral = Eigen::Vector3d::UnitX();  // along the beam
  EXPECT_THROW((void)measure(m, s), pkm::InvalidArgument);
  s.name.clear();
  EXPECT_THROW(s.validate(), pkm::InvalidArgument);
}

}  // namespace PKM_TEST_NS
