// Google Benchmark: hexapod IK, FK warm start (one servo step on a smooth 1 kHz path), FK cold
// start (from home), and the genhexkins-style iteration (tests/support/genhexkins_style.hpp) as a
// baseline.
#include <benchmark/benchmark.h>

#include <numbers>
#include <vector>

#include "pkm/kinematics/hexapod_checks.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/genhexkins_style.hpp"
#include "support/sample_models.hpp"

namespace {

using namespace pkm::kinematics;

/// A smooth path sampled at 1 kHz: 0.1 s per revolution-of-features scale, speeds ~ 50 in/min.
struct PathFixture {
  HexapodModel model = pkm::test::linuxcncSimModel();
  std::vector<PoseRpy> poses;
  std::vector<StrutVector> lengths;
  PathFixture() {
    HexapodData data(model);
    const int n = 10000;
    for (int k = 0; k < n; ++k) {
      const double t = 2 * std::numbers::pi * k / n;
      PoseRpy p = model.home;
      p.position += Eigen::Vector3d(3 * std::sin(t), 3 * (1 - std::cos(t)), std::sin(2 * t));
      p.rpy += Eigen::Vector3d(0.15 * std::sin(t), 0.12 * std::sin(3 * t), 0.2 * std::sin(t));
      poses.push_back(p);
      lengths.push_back(inverseKinematics(model, data, p));
    }
  }
};

const PathFixture& fixture() {
  static const PathFixture f;
  return f;
}

void BM_HexapodIk(benchmark::State& state) {
  const auto& f = fixture();
  HexapodData data(f.model);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(inverseKinematics(f.model, data, f.poses[k]));
    k = (k + 1) % f.poses.size();
  }
}
BENCHMARK(BM_HexapodIk);

void BM_HexapodIkWithJacobian(benchmark::State& state) {
  const auto& f = fixture();
  HexapodData data(f.model);
  std::size_t k = 0;
  for (auto _ : state) {
    inverseKinematics(f.model, data, f.poses[k]);
    benchmark::DoNotOptimize(computeStrutJacobian(f.model, data));
    k = (k + 1) % f.poses.size();
  }
}
BENCHMARK(BM_HexapodIkWithJacobian);

void BM_HexapodCheckPose(benchmark::State& state) {
  const auto& f = fixture();
  HexapodData data(f.model);
  std::size_t k = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(checkPose(f.model, data, f.poses[k]));
    k = (k + 1) % f.poses.size();
  }
}
BENCHMARK(BM_HexapodCheckPose);

void BM_HexapodFkWarm(benchmark::State& state) {
  const auto& f = fixture();
  HexapodData data(f.model);
  std::size_t k = 1;
  long iterations = 0;
  for (auto _ : state) {
    const FkSummary s = forwardKinematics(f.model, data, f.lengths[k], f.poses[k - 1]);
    iterations += s.iterations;
    benchmark::DoNotOptimize(data.pose);
    k = k + 1 < f.poses.size() ? k + 1 : 1;
  }
  state.counters["newton_steps"] =
      benchmark::Counter(static_cast<double>(iterations), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_HexapodFkWarm);

void BM_HexapodFkCold(benchmark::State& state) {
  const auto& f = fixture();
  HexapodData data(f.model);
  std::size_t k = 0;
  long iterations = 0;
  for (auto _ : state) {
    const FkSummary s = forwardKinematics(f.model, data, f.lengths[k], f.model.home);
    iterations += s.iterations;
    benchmark::DoNotOptimize(data.pose);
    k = (k + 97) % f.poses.size();
  }
  state.counters["newton_steps"] =
      benchmark::Counter(static_cast<double>(iterations), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_HexapodFkCold);

void BM_GenhexkinsStyleFkWarm(benchmark::State& state) {
  const auto& f = fixture();
  std::size_t k = 1;
  long iterations = 0;
  for (auto _ : state) {
    const auto r = pkm::test::genhexkinsStyleFk(f.model, f.lengths[k], f.poses[k - 1]);
    iterations += r.iterations;
    benchmark::DoNotOptimize(r);
    k = k + 1 < f.poses.size() ? k + 1 : 1;
  }
  state.counters["newton_steps"] =
      benchmark::Counter(static_cast<double>(iterations), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_GenhexkinsStyleFkWarm);

void BM_GenhexkinsStyleFkCold(benchmark::State& state) {
  const auto& f = fixture();
  std::size_t k = 0;
  long iterations = 0;
  for (auto _ : state) {
    const auto r = pkm::test::genhexkinsStyleFk(f.model, f.lengths[k], f.model.home);
    iterations += r.iterations;
    benchmark::DoNotOptimize(r);
    k = (k + 97) % f.poses.size();
  }
  state.counters["newton_steps"] =
      benchmark::Counter(static_cast<double>(iterations), benchmark::Counter::kAvgIterations);
}
BENCHMARK(BM_GenhexkinsStyleFkCold);

}  // namespace

BENCHMARK_MAIN();
