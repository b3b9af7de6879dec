// Google Benchmark: hexapod calibration (target: 42 parameters from 200 poses in under
// 100 ms): full-pose identification in the base frame and in a tracker frame (48 unknowns), the
// identification Jacobian and the identifiability SVD, and pose planning.
#include <benchmark/benchmark.h>

#include <random>

#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/calibration/pose_planning.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_checks.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/sample_models.hpp"

namespace {

using namespace pkm;

/// The 6-6 test machine with ±0.5 mm joint and ±1 mm offset errors, 200 poses with 5 µm noise.
struct Fixture {
  kinematics::HexapodModel nominal = test::millingModel();
  calibration::HexapodCalibrationData data, tracker;
  std::vector<kinematics::PoseRpy> candidates;
  Fixture() {
    std::mt19937 rng(20261122u);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::normal_distribution<double> n(0.0, 0.005);
    calibration::HexapodParameterVector p = calibration::hexapodParameters(nominal);
    for (int k = 0; k < calibration::kHexapodParameters; ++k)
      p(k) += (k % 7 == 6 ? 1.0 : 0.5) * u(rng);
    const kinematics::HexapodModel truth = calibration::withHexapodParameters(nominal, p);
    kinematics::HexapodData work(truth);
    geometry::RigidTransform f;
    f.linear() = geometry::rotationFromRpy(Eigen::Vector3d(0.001, -0.002, 2.6));
    f.translation() = Eigen::Vector3d(1500, -900, 350);
    for (int k = 0; k < 200; ++k) {
      const kinematics::PoseRpy pose = test::randomPose(rng, truth.home, 120.0, 0.12);
      calibration::PoseObservation o;
      o.readings = kinematics::inverseKinematics(truth, work, pose);
      o.pose = pose;
      for (int i = 0; i < 3; ++i) o.pose.position(i) += n(rng);
      data.poses.push_back(o);
      o.pose.position = f.linear().transpose() * (o.pose.position - f.translation());
      o.pose.rpy =
          geometry::rpyFromRotation(f.linear().transpose() * geometry::rotationFromRpy(o.pose.rpy));
      tracker.poses.push_back(o);
    }
    tracker.measurement_frame = calibration::initialMeasurementFrame(nominal, tracker);
    kinematics::HexapodData nd(nominal);
    while (candidates.size() < 1000) {
      const auto pose = test::randomPose(rng, nominal.home, 150.0, 0.15);
      if (kinematics::checkPose(nominal, nd, pose).ok()) candidates.push_back(pose);
    }
  }
};

const Fixture& fixture() {
  static const Fixture f;
  return f;
}

void BM_Calibrate200PosesBaseFrame(benchmark::State& state) {
  const Fixture& f = fixture();
  for (auto _ : state) {
    auto s = calibration::calibrateHexapod(f.nominal, f.data);
    benchmark::DoNotOptimize(s.parameters.data());
    state.counters["iterations"] = s.iterations;
  }
}
BENCHMARK(BM_Calibrate200PosesBaseFrame)->Unit(benchmark::kMillisecond);

void BM_Calibrate200PosesTrackerFrame(benchmark::State& state) {
  const Fixture& f = fixture();
  for (auto _ : state) {
    auto s = calibration::calibrateHexapod(f.nominal, f.tracker);
    benchmark::DoNotOptimize(s.parameters.data());
    state.counters["iterations"] = s.iterations;
  }
}
BENCHMARK(BM_Calibrate200PosesTrackerFrame)->Unit(benchmark::kMillisecond);

void BM_IdentificationJacobianAndSvd(benchmark::State& state) {
  const Fixture& f = fixture();
  std::vector<std::string> names;
  for (int k = 0; k < calibration::kHexapodParameters; ++k)
    names.push_back(calibration::hexapodParameterName(k));
  for (auto _ : state) {
    const Eigen::MatrixXd J = calibration::identificationJacobian(f.nominal, f.data);
    auto id = calibration::analyseIdentifiability(J, names);
    benchmark::DoNotOptimize(id.rank);
  }
}
BENCHMARK(BM_IdentificationJacobianAndSvd)->Unit(benchmark::kMillisecond);

void BM_PlanPoses(benchmark::State& state) {
  const Fixture& f = fixture();
  calibration::PosePlanOptions options;
  options.count = static_cast<int>(state.range(0));
  for (auto _ : state) {
    auto plan = calibration::planHexapodPoses(f.nominal, f.candidates, options);
    benchmark::DoNotOptimize(plan.index_value);
  }
}
BENCHMARK(BM_PlanPoses)->Arg(20)->Arg(50)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
