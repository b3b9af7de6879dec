#include "pkm/calibration/hybrid_calibration.hpp"

#include <gtest/gtest.h>

#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/simulation/hybrid_tracker.hpp"
#include "support/tolerances.hpp"

namespace pkm::calibration {
namespace PKM_TEST_NS {

constexpr double kExactSquareness = 1e-8;  // rad, noise-free data
constexpr double kNoise = 0.005;           // mm, tracker range noise in the noisy test
constexpr double kNoisySquareness = 5e-6;  // rad: 5 µm over ~1 m lever arms, a few σ

struct Bench {
  io::ExechonMachine machine = io::loadExechonMachine("mxt700s-like");
  kinematics::GeometricErrors errors = io::loadGeometricErrors("mxt700s-seed000");
  simulation::HybridVirtualMachine vm{*machine.hybrid, errors};

  simulation::HybridTrackerSetup tracker(int count, double sigma) const {
    simulation::HybridTrackerSetup s;
    s.name = "hybrid";
    s.count = count;
    s.x2 = Eigen::Vector2d(0, 3000);
    s.y2 = Eigen::Vector2d(0, 450);
    s.pkm_min = Eigen::Vector3d(-300, -300, -100);
    s.pkm_max = Eigen::Vector3d(300, 300, 300);
    s.smr_offset = Eigen::Vector3d(0, 0, 50);
    s.noise.range_sigma = sigma;
    s.work_T_tracker.translation() = Eigen::Vector3d(1500, 2500, 300);
    s.work_T_tracker.linear() =
        Eigen::AngleAxisd(-2.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return s;
  }

  HybridCalibrationData data(int count, double sigma, bool tracker_frame) {
    const simulation::HybridTrackerSetup s = tracker(count, sigma);
    simulation::RandomStream rng(test::kSeed);
    HybridCalibrationData d;
    d.target_offset = s.smr_offset;
    for (const auto& r : simulation::simulateHybridTracker(vm, s, rng)) {
      HybridObservation o;
      o.command = r.command;
      o.point = tracker_frame ? r.measured : Eigen::Vector3d(s.work_T_tracker * r.measured);
      o.source = "h.csv:" + std::to_string(d.observations.size() + 2);
      d.observations.push_back(o);
    }
    if (tracker_frame) {
      // A rough start: the placement to about a degree and 10 mm.
      d.measurement_frame = geometry::makeTransform(
          Eigen::AngleAxisd(-2.02, Eigen::Vector3d::UnitZ()).toRotationMatrix(),
          Eigen::Vector3d(1490, 2510, 305));
    }
    return d;
  }
};

void expectSquareness(const kinematics::HybridSquareness& a,
                      const kinematics::HybridSquareness& b,
                      double tol) {
  EXPECT_NEAR(a.sz_x2, b.sz_x2, tol);
  EXPECT_NEAR(a.sx_p, b.sx_p, tol);
  EXPECT_NEAR(a.sy_p, b.sy_p, tol);
  EXPECT_NEAR(a.sz_p, b.sz_p, tol);
}

TEST(HybridCalibration, RecoversTheFourSquarenessErrorsFromExactWorkFrameData) {
  Bench s;
  const HybridCalibrationSummary sum =
      calibrateHybridSquareness(*s.machine.hybrid, s.errors, s.data(60, 0.0, false));
  expectSquareness(sum.squareness, s.errors.squareness, kExactSquareness);
  EXPECT_TRUE(sum.identifiability.fullRank());
  EXPECT_GT(sum.before.max, 1.0);  // seed 000's 14.7 mrad tilt over hundreds of mm
  EXPECT_LT(sum.after.max, 1e-6);
}

TEST(HybridCalibration, NoisyTrackerFrameDataStillSeparatesSquarenessFromPlacement) {
  Bench s;
  const HybridCalibrationSummary sum =
      calibrateHybridSquareness(*s.machine.hybrid, s.errors, s.data(200, kNoise, true));
  ASSERT_TRUE(sum.measurement_frame.has_value());
  EXPECT_EQ(sum.identifiability.parameters, 10);
  EXPECT_TRUE(sum.identifiability.fullRank()) << sum.identifiability.rank;
  expectSquareness(sum.squareness, s.errors.squareness, kNoisySquareness);
  for (int k = 0; k < 4; ++k) EXPECT_GT(sum.standard_deviation(k), 0.0);
  EXPECT_LT(sum.after.rms, 2 * kNoise);
}

/// With the tracker's placement unknown and X2 never moving, szX2 only turns the whole PKM about
/// z, which szP does as well: only their difference is seen, and the report says so.
TEST(HybridCalibration, AnUnmovedX2CannotSeparateSzX2FromSzP) {
  Bench s;
  HybridCalibrationData d = s.data(40, 0.0, true);
  const geometry::RigidTransform tracker_T_work = s.tracker(1, 0.0).work_T_tracker.inverse();
  for (auto& o : d.observations) {
    o.command.x2 = 1000.0;  // X2 never moves; re-measure exactly at the changed command
    Eigen::VectorXd c(5);
    c << o.command.x2, o.command.y2, o.command.pkm;
    o.point = tracker_T_work * (s.vm.moveTo(c) * d.target_offset);
  }
  const HybridCalibrationSummary sum = calibrateHybridSquareness(*s.machine.hybrid, s.errors, d);
  EXPECT_FALSE(sum.identifiability.fullRank());
  ASSERT_FALSE(sum.identifiability.combinations.empty());
  bool sz_x2 = false, sz_p = false;
  for (const auto& [name, coef] : sum.identifiability.combinations.front().terms) {
    sz_x2 = sz_x2 || name == "szX2";
    sz_p = sz_p || name == "szP";
  }
  EXPECT_TRUE(sz_x2 && sz_p);
}

TEST(HybridCalibration, BadInputIsRejected) {
  Bench s;
  HybridCalibrationData d = s.data(10, 0.0, false);
  d.observations[3].point.x() = std::nan("");
  try {
    (void)calibrateHybridSquareness(*s.machine.hybrid, s.errors, d);
    ADD_FAILURE();
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("h.csv:5"), std::string::npos) << e.what();
  }
  HybridCalibrationData one = s.data(1, 0.0, false);
  EXPECT_THROW((void)calibrateHybridSquareness(*s.machine.hybrid, s.errors, one), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration

namespace pkm::calibration {
namespace PKM_TEST_NS {

TEST(HybridCalibration, ConvergesInAFewIterationsOnNoisyTrackerData) {
  constexpr int kMaxIterations = 12;       ///< LM iterations (rejected steps included)
  constexpr double kTolStationary = 1e-9;  ///< rad: default vs strict stopping rules
  Bench s;
  const HybridCalibrationData data = s.data(200, kNoise, true);
  const HybridCalibrationSummary sum = calibrateHybridSquareness(*s.machine.hybrid, s.errors, data);
  EXPECT_TRUE(sum.converged) << sum.termination;
  EXPECT_LE(sum.iterations, kMaxIterations) << sum.termination;
  RecordProperty("iterations", sum.iterations);
  expectSquareness(sum.squareness, s.errors.squareness, kNoisySquareness);
  // Stationary: stopping rules far below the noise floor find the same minimum.
  HybridCalibrationOptions strict;
  strict.function_tolerance = 1e-16;
  strict.gradient_tolerance = 1e-16;
  strict.parameter_tolerance = 1e-16;
  strict.max_iterations = 200;
  const HybridCalibrationSummary tight =
      calibrateHybridSquareness(*s.machine.hybrid, s.errors, data, strict);
  expectSquareness(tight.squareness, sum.squareness, kTolStationary);
  HybridCalibrationOptions bad;
  bad.function_tolerance = -1.0;
  EXPECT_THROW((void)calibrateHybridSquareness(*s.machine.hybrid, s.errors, data, bad),
               InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration
